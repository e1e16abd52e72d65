// Issue 43: every mesh file that ever crashed, hung or blew up memory in the loader (hand-made
// for each case the mutation campaign found, and what fuzz_mesh found since), replayed with
// the harness's own checks (fuzz/mesh_replay.h): a usable mesh or a MeshError, in bounded time.
// CI has no libFuzzer; this is where the corpus runs. The cases the issue names are also checked
// for their message: the file, the line and the element at fault.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "tianracer_sim/mesh/mesh_loader.h"

#include "../../fuzz/mesh_replay.h"
#include "common_test_support.h"

namespace tianracer_sim {
namespace {

using ::testing::HasSubstr;

const std::string kCorpus = std::string(TEST_DATA_DIR) + "/fuzz_regressions/mesh/";

std::vector<std::string> corpusFiles() {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::directory_iterator(kCorpus)) {
    const std::string name = e.path().filename().string();
    if (e.is_regular_file() && name != "README.md") out.push_back(e.path().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string errorOf(const std::string& file) {
  return test::errorText<MeshError>([&] { loadMeshFile(kCorpus + file); });
}

TEST(MeshFuzzRegressions, EveryFileLoadsOrIsACleanErrorInBoundedTime) {
  const std::vector<std::string> files = corpusFiles();
  ASSERT_GE(files.size(), 48u) << "the corpus is missing in " << kCorpus;
  for (const std::string& f : files) {
    const auto t0 = std::chrono::steady_clock::now();
    EXPECT_EQ(tianracer_sim_fuzz::replayMeshFile(f), "") << f;
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    // Each is a few kB; before the checks some took 12 GB and minutes.
    EXPECT_LT(s, 20.0) << f;
  }
}

TEST(MeshFuzzRegressions, TheValidTemplatesLoad) {
  for (const char* f : {"collada_valid_tetrahedron.dae", "collada_polylist_valid.dae", "obj_valid_triangle.obj"}) {
    const TriangleMesh m = loadMeshFile(kCorpus + f);
    EXPECT_GE(m.triangleCount(), 1u) << f;
  }
}

TEST(MeshFuzzRegressions, SkinsAreReadAsTheirSourceMeshAndTheirBrokenWeightsDoNotMatter) {
  // The loader keeps no bones: a skin's <vertex_weights> that crashed assimp (a joint or weight
  // index out of range: SIGSEGV, SIGABRT) or made it allocate 2e9 entries is not read, and the
  // mesh is the skin's source, where Gazebo and assimp place it.
  const TriangleMesh plain = loadMeshFile(kCorpus + "collada_valid_tetrahedron.dae");
  for (const char* f : {"collada_skin_valid.dae", "collada_skin_joint_index_out_of_range.dae",
                        "collada_skin_weight_index_out_of_range.dae", "collada_skin_vertex_weights_count_huge.dae"}) {
    const TriangleMesh m = loadMeshFile(kCorpus + f);
    EXPECT_EQ(m.triangleCount(), plain.triangleCount()) << f;
    EXPECT_TRUE(m.boundsMin().isApprox(plain.boundsMin()) && m.boundsMax().isApprox(plain.boundsMax())) << f;
  }
}

TEST(MeshFuzzRegressions, TheCrashesOfIssue43NameFileLineAndElement) {
  struct Case {
    const char* file;
    const char* expected;
  };
  const Case cases[] = {
      // assimp read out of bounds (SIGSEGV) or aborted (ai_assert, SIGABRT):
      {"collada_stride_huge.dae", "collada_stride_huge.dae:10: COLLADA <accessor source='#pos-array'>: stride "
                                  "4294967295 is above the limit of 268435456"},
      {"collada_stride_past_array.dae",
       "collada_stride_past_array.dae:10: COLLADA <accessor source='#pos-array'>: count 4, stride 100000000, "
       "offset 0 and 3 params read past the end of <float_array id='pos-array'> (line 8, 12 values)"},
      {"collada_accessor_count_zero.dae",
       "collada_accessor_count_zero.dae:18: COLLADA <p>: index 0 (number 1, offset 0) is out of range: its "
       "input has 0 elements"},
      {"collada_p_deleted.dae",
       "collada_p_deleted.dae:16: COLLADA <triangles>: count 4 but 0 <p> elements (COLLADA gives one list)"},
      {"collada_polylist_vcount_zero.dae",
       "collada_polylist_vcount_zero.dae:18: COLLADA <vcount>: entry '0' is not a vertex count"},
      {"collada_polylist_vcount_deleted.dae",
       "collada_polylist_vcount_deleted.dae:16: COLLADA <polylist>: count 4 but 0 <vcount> elements"},
      {"collada_polygons_count_zero.dae", "collada_polygons_count_zero.dae:16: COLLADA <polygons>: count 0 but 1 <p>"},
      {"collada_node_instances_itself.dae",
       "collada_node_instances_itself.dae:26: COLLADA <instance_node url='#a'>: instances a node inside itself "
       "('a' -> 'a'): a node cycle"},
      {"collada_node_cycle.dae", "('a' -> 'b' -> 'a'): a node cycle"},
      {"collada_node_instances_the_scene.dae", "('scene' -> 'a' -> 'scene'): a node cycle"},
      // memory without bound:
      {"collada_p_stray_character.dae",
       "collada_p_stray_character.dae:18: COLLADA <p>: index 'x3' (number 8) is not a non-negative integer"},
      {"collada_float_array_count_huge.dae",
       "collada_float_array_count_huge.dae:8: COLLADA <float_array id='pos-array'>: count 2000000000 is above"},
      {"collada_triangles_count_huge.dae", "COLLADA <triangles>: count 2000000000 is above the limit of 10000000"},
      {"collada_nodes_instanced_2_to_the_40.dae", "the scene expands to more than 1000000 nodes (the limit)"},
      // assimp's own errors before, now named (the last one an allocation error):
      {"collada_p_too_short.dae", "collada_p_too_short.dae:18: COLLADA <p>: holds 11 vertices; count 4 triangles need 12"},
      {"collada_polylist_vcount_sum_mismatch.dae",
       "collada_polylist_vcount_sum_mismatch.dae:19: COLLADA <p>: holds 12 vertices; the <vcount> entries add up to 11"},
      {"collada_p_not_whole_vertices.dae",
       "COLLADA <p>: 23 indices are not a whole number of vertices of 2 indices (the inputs' offsets)"},
      {"collada_tristrips_empty_p.dae", "COLLADA <p>: holds 0 vertices; a tristrip needs 3"},
      {"collada_input_offset_huge.dae", "COLLADA <input source='#v'>: offset 4000000000 is above the limit of 255"},
      {"collada_no_vertex_input.dae", "COLLADA <triangles>: has no VERTEX input"},
      {"collada_vertex_input_names_other_vertices.dae",
       "COLLADA <input source='#w'>: source '#w' is not this mesh's <vertices> ('#v')"},
      {"collada_vertices_without_position.dae", "its <vertices> '#v' has no POSITION input"},
      {"collada_polylist_vcount_deleted.dae", "count 4 but 0 <vcount> elements (a polylist gives one)"},
      {"collada_polylist_vcount_short.dae", "COLLADA <vcount>: holds 2 entries for count 4"},
      // accepted before with wrong geometry:
      {"collada_accessor_count_above_array.dae", "read past the end of <float_array id='pos-array'>"},
      {"collada_p_negative_index.dae", "COLLADA <p>: index '-3' (number 6) is not a non-negative integer"},
      {"stl_binary_vertex_1e30.stl", "vertex 1 at (1e+30, 0, 0) is out of range: farther than 1e+06 m"},
      {"obj_vertex_1e30.obj", "vertex 1 at (1e+30, 0, 0) is out of range"},
  };
  for (const Case& c : cases) EXPECT_THAT(errorOf(c.file), HasSubstr(c.expected)) << c.file;
}

TEST(MeshFuzzRegressions, ADirectoryADeviceOrAFifoIsSaidToBeOneAndNotRead) {
  const std::string dir = kCorpus.substr(0, kCorpus.size() - 1);
  EXPECT_THAT(test::errorText<MeshError>([&] { loadMeshFile(dir); }),
              HasSubstr("mesh '" + dir + "': is a directory, not a mesh file"));
  // Reading /dev/zero never ends and a fifo blocks until a writer comes: stat() says what they are.
  EXPECT_THAT(test::errorText<MeshError>([] { loadMeshFile("/dev/zero"); }),
              HasSubstr("mesh '/dev/zero': is not a regular file (a character device)"));
  char tmpl[] = "/tmp/test_mesh_fifo_XXXXXX";
  ASSERT_NE(::mkdtemp(tmpl), nullptr);
  const std::string fifo = std::string(tmpl) + "/mesh.stl";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_THAT(test::errorText<MeshError>([&] { loadMeshFile(fifo); }),
              HasSubstr("mesh '" + fifo + "': is not a regular file (a pipe (fifo))"));
  ::unlink(fifo.c_str());
  ::rmdir(tmpl);
  EXPECT_THAT(test::errorText<MeshError>([] { loadMeshFile("/nonexistent/mesh.stl"); }),
              HasSubstr("mesh '/nonexistent/mesh.stl': file not found"));
}

TEST(MeshFuzzRegressions, AFileAbove256MiBIsRefusedBeforeItIsRead) {
  // A sparse file: no disk, and nothing is read (a binary STL of 5.6e6 facets by its size).
  char tmpl[] = "/tmp/test_mesh_big_XXXXXX";
  ASSERT_NE(::mkdtemp(tmpl), nullptr);
  const std::string big = std::string(tmpl) + "/big.stl";
  const off_t size = (256ll << 20) + 84;
  FILE* f = std::fopen(big.c_str(), "wb");
  ASSERT_NE(f, nullptr);
  ASSERT_EQ(::ftruncate(fileno(f), size), 0);
  std::fclose(f);
  EXPECT_THAT(test::errorText<MeshError>([&] { loadMeshFile(big); }),
              HasSubstr("mesh '" + big + "': 268435540 bytes, above the limit of 268435456 bytes (256 MiB)"));
  ::unlink(big.c_str());
  ::rmdir(tmpl);
}

}  // namespace
}  // namespace tianracer_sim
