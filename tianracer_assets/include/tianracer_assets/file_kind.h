// What a path names when it is not a regular file. Header-only: the model and world loaders
// (which link no assimp) and the mesh loader say the same thing of a mesh URI that names a
// directory or a device. ROS-free.
#ifndef TIANRACER_ASSETS_FILE_KIND_H
#define TIANRACER_ASSETS_FILE_KIND_H

#include <sys/stat.h>

#include <string>

namespace tianracer_assets {

/// "" for a regular file; else what the path is instead: "file not found", "is a directory,
/// not a mesh file", "is not a regular file (a character device)" (block device, pipe (fifo),
/// socket). stat() only: nothing is opened, so /dev/zero or a fifo cannot block or read forever.
inline std::string fileProblem(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return "file not found";
  if (S_ISREG(st.st_mode)) return "";
  if (S_ISDIR(st.st_mode)) return "is a directory, not a mesh file";
  const char* kind = S_ISCHR(st.st_mode)    ? "a character device"
                     : S_ISBLK(st.st_mode)  ? "a block device"
                     : S_ISFIFO(st.st_mode) ? "a pipe (fifo)"
                     : S_ISSOCK(st.st_mode) ? "a socket"
                                            : "not a file";
  return std::string("is not a regular file (") + kind + ")";
}

}  // namespace tianracer_assets

#endif  // TIANRACER_ASSETS_FILE_KIND_H
