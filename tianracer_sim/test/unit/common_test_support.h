// What the unit tests of every area share: files, temporary folders, edited text and the text of
// a thrown error. Header-only and free of the sim's libraries, so any test can include it.
#ifndef TIANRACER_SIM_TEST_COMMON_TEST_SUPPORT_H
#define TIANRACER_SIM_TEST_COMMON_TEST_SUPPORT_H

#include <stdlib.h>  // mkdtemp

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>

#include <gtest/gtest.h>

namespace tianracer_sim {
namespace test {

/// The whole file ("" if it cannot be read).
inline std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// A fresh folder under the system's temp folder, removed at the end of the test.
struct TempDir {
  std::filesystem::path path;
  /// `name` tells the test's folders apart: <tmp>/tianracer_<name>_XXXXXX.
  explicit TempDir(const std::string& name) {
    std::string tmpl =
        (std::filesystem::temp_directory_path() / ("tianracer_" + name + "_XXXXXX")).string();
    path = mkdtemp(tmpl.data());
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  std::string file(const std::string& rel) const { return (path / rel).string(); }
  /// Writes `text` to `rel` (creating its folders); returns the file's path.
  std::string write(const std::string& rel, const std::string& text) const {
    const std::filesystem::path p = path / rel;
    std::filesystem::create_directories(p.parent_path());
    std::ofstream(p) << text;
    return p.string();
  }
};

/// `s` with its first `from` replaced by `to`; a test failure (and `s` unchanged) when `from` is
/// not in it.
inline std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}

/// The what() of the E that f() throws; `none` when it throws nothing.
template <class E, class F>
std::string errorText(F&& f, const std::string& none = "") {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  return none;
}

}  // namespace test
}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_TEST_COMMON_TEST_SUPPORT_H
