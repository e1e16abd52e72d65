// Runs the xacro tool. posix_spawnp (no shell, so no quoting issues); stdout through a pipe,
// stderr into an unlinked temporary file so that neither stream can block the other; stdin is
// /dev/null so xacro can never wait for input.
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "model_internal.h"

extern char** environ;

namespace tianracer_sim {

namespace {

std::string readAll(int fd) {
  std::string out;
  char buf[65536];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n > 0) {
      out.append(buf, static_cast<size_t>(n));
    } else if (n == 0 || errno != EINTR) {
      break;
    }
  }
  return out;
}

struct Fd {
  int fd = -1;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

std::string expandXacro(const std::string& path, const std::vector<std::string>& args,
                        const WarningSink& warn) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw ModelError("xacro failed on " + path + ": file not found");

  const std::string fail = "xacro failed on " + path + ": ";
  char tmpl[] = "/tmp/tianracer_xacro_stderr_XXXXXX";
  Fd err;
  err.fd = ::mkostemp(tmpl, O_CLOEXEC);
  if (err.fd < 0) throw ModelError(fail + "cannot create a temporary file: " + std::strerror(errno));
  ::unlink(tmpl);
  int p[2];
  if (::pipe2(p, O_CLOEXEC) != 0) throw ModelError(fail + "pipe: " + std::strerror(errno));
  Fd out_r, out_w;
  out_r.fd = p[0];
  out_w.fd = p[1];

  std::vector<std::string> argv_s{"xacro", path};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, out_w.fd, 1);
  posix_spawn_file_actions_adddup2(&actions, err.fd, 2);
  pid_t pid = 0;
  const int rc = ::posix_spawnp(&pid, "xacro", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0)
    throw ModelError(fail + "cannot run xacro (" + std::strerror(rc) + "); is it on PATH?");
  ::close(out_w.fd);
  out_w.fd = -1;

  const std::string urdf = readAll(out_r.fd);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  ::lseek(err.fd, 0, SEEK_SET);
  const std::string errors = trimText(readAll(err.fd));

  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::string why = errors;
    if (why.empty())
      why = WIFEXITED(status) ? "exit status " + std::to_string(WEXITSTATUS(status))
                              : "killed by signal " + std::to_string(WTERMSIG(status));
    throw ModelError(fail + why);
  }
  if (!errors.empty() && warn) warn("xacro on " + path + ": " + errors);
  return urdf;
}

std::string expandXacro(const std::string& path, const std::vector<std::string>& args) {
  return expandXacro(path, args, WarningSink());
}

}  // namespace tianracer_sim
