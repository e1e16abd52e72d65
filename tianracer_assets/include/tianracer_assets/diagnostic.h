// The one diagnostic policy of the ROS-free libraries (tianracer_assets, tianracer_control and
// tianracer_sim; it lives in the package below the other two): an input that cannot be used raises InputError, which
// carries the file, line and element where they are known; a warning goes through a
// WarningSink, once (WarnOnce). Every message that names a place starts with it, in the form
// compilers use, "<file>:<line>: ". The nodes catch at one boundary and log. Header-only, so
// that every library of the three packages can use it without linking anything (Drake's parsers
// share one DiagnosticPolicy the same way).
#ifndef TIANRACER_ASSETS_DIAGNOSTIC_H
#define TIANRACER_ASSETS_DIAGNOSTIC_H

#include <functional>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>

namespace tianracer_assets {

/// Where in an input a problem is. Each part may be unknown (empty, 0).
struct SourceLocation {
  std::string file;     // a path, or what stands for one ("/robot_description", "model_xml")
  int line = 0;         // 1-based
  std::string element;  // the XML element's name, without brackets
};

/// The one location format: "<file>:<line>: ", "<file>: " without a line, "line <n>: " without
/// a file, "" when neither is known.
inline std::string formatLocation(const std::string& file, int line) {
  if (file.empty()) return line > 0 ? "line " + std::to_string(line) + ": " : std::string();
  return line > 0 ? file + ":" + std::to_string(line) + ": " : file + ": ";
}
inline std::string formatLocation(const SourceLocation& where) {
  return formatLocation(where.file, where.line);
}

/// An input (a model, world, mesh, image or parameter file, a parameter, a sensor block, the
/// host's OpenGL) that cannot be used. what() is formatLocation(where()) + message(), and the
/// message names the element and value at fault.
class InputError : public std::runtime_error {
 public:
  /// A message that names no place, or has it written in already.
  explicit InputError(const std::string& message) : std::runtime_error(message), message_(message) {}
  InputError(SourceLocation where, const std::string& message)
      : std::runtime_error(formatLocation(where) + message), where_(std::move(where)),
        message_(message) {}

  const SourceLocation& where() const { return where_; }
  /// what() without the location: a caller that adds context keeps the location in front,
  /// InputError(e.where(), "robot 'r': " + e.message()).
  const std::string& message() const { return message_; }

 private:
  SourceLocation where_;
  std::string message_;
};

/// Receives each warning (unknown tag or key, defaulted value, skipped visual...). May be
/// empty: warnings are then dropped.
using WarningSink = std::function<void(const std::string&)>;

/// Sends `text` to `sink` when there is one (an empty sink drops it).
inline void say(const WarningSink& sink, const std::string& text) {
  if (sink) sink(text);
}

/// Forwards a warning to its sink the first time it is seen. Not thread-safe: one per parser
/// or one per thread of use.
class WarnOnce {
 public:
  explicit WarnOnce(WarningSink sink = {}) : sink_(std::move(sink)) {}

  /// Forwards `message` unless it was seen before; true when it was new.
  bool operator()(const std::string& message) { return (*this)(message, message); }
  /// Forwards `message` once per `key`, and never the same message twice; true when forwarded
  /// (or would have been, to an empty sink).
  bool operator()(const std::string& key, const std::string& message) {
    if (!keys_.insert(key).second) return false;
    if (!messages_.insert(message).second) return false;
    if (sink_) sink_(message);
    return true;
  }

 private:
  WarningSink sink_;
  std::set<std::string> keys_;
  std::set<std::string> messages_;
};

}  // namespace tianracer_assets

#endif  // TIANRACER_ASSETS_DIAGNOSTIC_H
