// world_corpus: the worlds of Gazebo's source (worlds/**/*.world) through the ROS-free core, as
// a second corpus beside model_corpus (docs/gazebo_worlds.md). Run by hand, not in CI (it needs
// the mirrors):
//   world_corpus <gazebo source git dir> <gazebo_models git dir> [--only NAME]... [--seconds S]
//                [--wall-limit S] [--markdown FILE]
// Both arguments are bare git dirs (or work trees); their HEAD is extracted into a temp dir:
// the Gazebo source's worlds/, models/ and media/ (models/ on the model path, as Gazebo installs
// it into share/gazebo-11/models) and the model library (on the model path, as ~/.gazebo/models).
// For every world: whether it loads, what was left out (each error, and each warning that names
// an element not simulated), and every model's verdict over --seconds (30) of sim
// (corpus_judge.h: judgeInWorld, the last 10 s as the window). A world whose sim takes more
// than --wall-limit seconds (20) of wall clock is stopped and called slow (the run stays within
// ~15 minutes on one core).
#include <unistd.h>  // getpid

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <cstdio>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "corpus_judge.h"

namespace ts = tianracer_sim;
namespace fs = std::filesystem;
using namespace ts::corpus;

namespace {

// HEAD's `paths` (all: "") of the repository `git_dir` into `to`, every file the snapshot holds
// (a mirror may lack its largest blobs: git archive stops there; those are counted in *missing).
void extract(const std::string& git_dir, const std::string& paths, const fs::path& to, int* missing) {
  const fs::path list = to.string() + ".list";
  fs::create_directories(to);
  const std::string ls = "git --git-dir='" + git_dir + "' ls-tree -r HEAD " + paths + " > '" + list.string() + "'";
  if (std::system(ls.c_str()) != 0) throw std::runtime_error("could not list " + paths + " in " + git_dir);
  std::vector<std::pair<std::string, std::string>> blobs;  // sha, path
  {
    std::ifstream in(list);
    std::ofstream shas(list.string() + ".shas");
    for (std::string line; std::getline(in, line);) {
      const std::size_t tab = line.find('\t');
      std::istringstream head(line.substr(0, tab));
      std::string mode, type, sha;
      head >> mode >> type >> sha;
      if (type != "blob" || tab == std::string::npos) continue;
      blobs.emplace_back(sha, line.substr(tab + 1));
      shas << sha << "\n";
    }
  }
  const std::string cat = "git --git-dir='" + git_dir + "' cat-file --batch < '" + list.string() + ".shas'";
  FILE* out = popen(cat.c_str(), "r");
  if (!out) throw std::runtime_error("could not read " + git_dir);
  for (const auto& [sha, path] : blobs) {
    char header[256];
    if (!std::fgets(header, sizeof header, out)) break;
    std::istringstream h(header);
    std::string got, type;
    std::size_t size = 0;
    h >> got >> type >> size;
    if (type != "blob") {
      ++*missing;
      continue;
    }
    std::string data(size, '\0');
    if (size && std::fread(&data[0], 1, size, out) != size) break;
    std::fgetc(out);  // the newline after the contents
    const fs::path file = to / path;
    fs::create_directories(file.parent_path());
    std::ofstream(file, std::ios::binary) << data;
  }
  pclose(out);
  fs::remove(list);
  fs::remove(list.string() + ".shas");
}

std::string gitDir(const std::string& d) {
  return fs::exists(fs::path(d) / ".git") ? (fs::path(d) / ".git").string() : d;
}

struct WorldResult {
  std::string name;
  bool loads = false;
  std::string error;
  std::vector<std::string> left_out, warnings;
  std::vector<Judged> models;
  double load_ms = 0.0, sim_ms = 0.0;
  std::string verdict, why;
};

WorldResult run(const fs::path& file, const std::string& name, const std::vector<std::string>& model_paths,
                double seconds, double window, double wall_limit) {
  WorldResult r;
  r.name = name;
  ts::WorldLoadOptions options;
  options.model_paths = model_paths;
  options.warn = [&](const std::string& w) { r.warnings.push_back(w); };
  options.error = [&](const std::string& e) { r.left_out.push_back(e); };
  const auto t0 = std::chrono::steady_clock::now();
  ts::WorldDescription world;
  try {
    world = ts::loadWorldFile(file.string(), options);
  } catch (const std::exception& e) {
    r.verdict = "fails";
    r.why = r.error = e.what();
    return r;
  }
  r.load_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  r.loads = true;
  const auto t1 = std::chrono::steady_clock::now();
  try {
    r.models = runWorld(world, seconds, window, [&](const std::string& w) { r.warnings.push_back(w); },
                        wall_limit);
  } catch (const OutOfTime& e) {
    r.verdict = "slow";
    r.why = e.what();
    return r;
  } catch (const std::exception& e) {
    r.verdict = "fails";
    r.why = std::string("physics: ") + e.what();
    return r;
  }
  r.sim_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t1).count();
  std::map<std::string, int> counts;
  for (const Judged& m : r.models) {
    ++counts[m.verdict];
    if (m.verdict == "differs") r.why += (r.why.empty() ? "" : "; ") + m.name + " " + m.why;
  }
  r.verdict = counts["differs"] ? "differs" : (r.left_out.empty() ? "loads" : "partly");
  // Actors are played by their script (world/actor.h), not judged: say what each does.
  for (const ts::ActorDescription& a : world.actors) {
    std::ostringstream os;
    os << "actor " << a.model.name << ": ";
    if (a.script.trajectories.empty()) {
      os << "no <trajectory>, stands at its <pose>";
    } else {
      ts::ActorPlayer player(a.script, a.model.X_WM, world.physics.max_step_size);
      os << a.script.trajectories.size() << " trajectory(ies), " << player.scriptLength() << " s"
         << (a.script.loop ? " looped" : "") << (a.script.auto_start ? "" : ", waits for Play()");
    }
    os << ", " << a.model.links.size() << " link(s)";
    r.why += (r.why.empty() ? "" : "; ") + os.str();
  }
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> dirs, only;
  std::string markdown;
  double seconds = 30.0, window = 10.0, wall_limit = 20.0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() { return optionValue(argc, argv, &i); };
    if (a == "--only") only.push_back(next());
    else if (a == "--seconds") seconds = std::stod(next());
    else if (a == "--markdown") markdown = next();
    else if (a == "--wall-limit") wall_limit = std::stod(next());
    else if (!a.empty() && a[0] == '-') dirs.clear(), dirs.push_back("-");
    else dirs.push_back(a);
  }
  if (dirs.size() != 2 || !fs::is_directory(dirs[0]) || !fs::is_directory(dirs[1]) || seconds <= window) {
    std::cerr << "usage: world_corpus <gazebo source git dir> <gazebo_models git dir> [--only NAME]... "
                 "[--seconds S > 10] [--wall-limit S] [--markdown FILE]\n";
    return 2;
  }
  const fs::path tmp = fs::temp_directory_path() / ("world_corpus." + std::to_string(::getpid()));
  const fs::path gazebo = tmp / "gazebo", library = tmp / "models";
  int missing = 0;  // files the snapshots lack
  try {
    extract(gitDir(dirs[0]), "worlds models media", gazebo, &missing);
    extract(gitDir(dirs[1]), "", library, &missing);
  } catch (const std::exception& e) {
    std::cerr << "world_corpus: " << e.what() << "\n";
    fs::remove_all(tmp);
    return 1;
  }
  // Gazebo's install: share/gazebo-11/{models,media}; the model library as ~/.gazebo/models.
  const std::vector<std::string> model_paths = {(gazebo / "models").string(), library.string(), gazebo.string()};
  if (missing) std::cout << "the snapshots lack " << missing << " files (their largest): they are left out\n";
  std::vector<std::pair<std::string, fs::path>> worlds;
  for (const auto& e : fs::recursive_directory_iterator(gazebo / "worlds")) {
    if (e.path().extension() != ".world") continue;
    const std::string n = fs::relative(e.path(), gazebo / "worlds").string();
    if (only.empty() || std::find(only.begin(), only.end(), n) != only.end()) worlds.emplace_back(n, e.path());
  }
  std::sort(worlds.begin(), worlds.end());

  std::vector<WorldResult> results;
  std::map<std::string, int> counts, model_counts;
  double load_ms = 0.0, sim_ms = 0.0;
  const std::string root = tmp.string();
  for (const auto& [n, path] : worlds) {
    std::cerr << n << "... " << std::flush;
    results.push_back(run(path, n, model_paths, seconds, window, wall_limit));
    const WorldResult& r = results.back();
    ++counts[r.verdict];
    for (const Judged& m : r.models) ++model_counts[m.verdict];
    load_ms += r.load_ms;
    sim_ms += r.sim_ms;
    std::cout << n << ": " << r.verdict << ", " << r.models.size() << " models, " << r.left_out.size()
              << " left out, " << fmt(r.sim_ms / 1000.0, 1) << " s"
              << (r.why.empty() ? "" : " (" + cell(r.why, root).substr(0, 200) + ")") << std::endl;
  }

  std::ostringstream md;
  md << "| world | verdict | models: verdicts | left out (errors) | not simulated (warnings) | why |\n"
        "|---|---|---|---|---|---|\n";
  for (const WorldResult& r : results) {
    std::map<std::string, int> c;
    for (const Judged& m : r.models) ++c[m.verdict];
    std::string cs;
    for (const auto& kv : c) cs += (cs.empty() ? "" : ", ") + std::to_string(kv.second) + " " + kv.first;
    std::string lo, wa;
    for (const std::string& e : r.left_out) lo += (lo.empty() ? "" : "<br>") + cell(e, root);
    for (const std::string& w : r.warnings) wa += (wa.empty() ? "" : "<br>") + cell(w, root);
    std::string why = cell(r.why, root);
    for (const Judged& m : r.models)
      if (m.verdict == "moves") why += (why.empty() ? "" : "; ") + m.name + " moves: " + cell(m.why, root);
    md << "| " << r.name << " | " << r.verdict << " | " << r.models.size() << ": " << cs << " | " << lo << " | "
       << wa << " | " << why << " |\n";
  }
  md << "\n" << results.size() << " worlds:";
  for (const auto& kv : counts) md << " " << kv.second << " " << kv.first << ",";
  md.seekp(-1, std::ios::cur);
  md << ". Their models:";
  for (const auto& kv : model_counts) md << " " << kv.second << " " << kv.first << ",";
  md.seekp(-1, std::ios::cur);
  md << ".\n\nLoading every world: " << fmt(load_ms, 0) << " ms; physics set-up and " << fmt(seconds, 0)
     << " s of sim per world: " << fmt(sim_ms / 1000.0, 1) << " s.\n";
  std::cout << md.str();
  if (!markdown.empty()) std::ofstream(markdown) << md.str();
  fs::remove_all(tmp);
  return 0;
}
