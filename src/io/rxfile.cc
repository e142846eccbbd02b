#include "io/rxfile.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>

#include "util/error.h"
#include "util/strings.h"

namespace tsrir {
namespace {

std::string where(const std::string& rx, const std::string& context) {
  return context.empty() ? rx : context + ": " + rx;
}

std::vector<char> read_stream(std::istream& in) {
  std::vector<char> data;
  char buf[1 << 16];
  while (in.read(buf, sizeof buf) || in.gcount() > 0) data.insert(data.end(), buf, buf + in.gcount());
  return data;
}

}  // namespace

bool is_pipe_rxfilename(const std::string& rx) {
  std::string t = trim(rx);
  return !t.empty() && t.back() == '|';
}

std::vector<char> run_command_capture(const std::string& command, const std::string& context) {
  int out_pipe[2], err_pipe[2];
  if (pipe(out_pipe) != 0 || pipe(err_pipe) != 0) throw Error("pipe() failed: " + std::string(std::strerror(errno)));
  pid_t pid = fork();
  if (pid < 0) throw Error("fork() failed: " + std::string(std::strerror(errno)));
  if (pid == 0) {
    dup2(out_pipe[1], 1);
    dup2(err_pipe[1], 2);
    close(out_pipe[0]);
    close(out_pipe[1]);
    close(err_pipe[0]);
    close(err_pipe[1]);
    execl("/bin/bash", "bash", "-c", command.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  close(out_pipe[1]);
  close(err_pipe[1]);
  std::vector<char> out;
  std::string err;
  struct pollfd fds[2] = {{out_pipe[0], POLLIN, 0}, {err_pipe[0], POLLIN, 0}};
  int open_fds = 2;
  char buf[1 << 16];
  while (open_fds > 0) {
    if (poll(fds, 2, -1) < 0) {
      if (errno == EINTR) continue;
      break;
    }
    for (auto& f : fds) {
      if (f.fd < 0 || !(f.revents & (POLLIN | POLLHUP | POLLERR))) continue;
      ssize_t n = read(f.fd, buf, sizeof buf);
      if (n > 0) {
        if (f.fd == out_pipe[0])
          out.insert(out.end(), buf, buf + n);
        else if (err.size() < 8192)
          err.append(buf, static_cast<size_t>(n));
      } else if (n == 0 || (n < 0 && errno != EINTR)) {
        close(f.fd);
        f.fd = -1;
        --open_fds;
      }
    }
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  std::string cmd_name = context.empty() ? "command '" + command + "'" : context + ": command '" + command + "'";
  if (WIFSIGNALED(status)) {
    throw Error(cmd_name + " was killed by signal " + std::to_string(WTERMSIG(status)) +
                (err.empty() ? "" : "; its stderr: " + trim(err)));
  }
  if (WEXITSTATUS(status) != 0) {
    throw Error(cmd_name + " failed with exit status " + std::to_string(WEXITSTATUS(status)) +
                (err.empty() ? "" : "; its stderr: " + trim(err)));
  }
  if (!err.empty()) std::cerr << err;
  return out;
}

std::vector<char> read_rxfile(const std::string& rx, const std::string& context) {
  std::string t = trim(rx);
  if (t.empty()) throw Error((context.empty() ? std::string("") : context + ": ") + "empty file name");
  if (t == "-") return read_stream(std::cin);
  if (t.back() == '|') {
    std::string cmd = trim(t.substr(0, t.size() - 1));
    if (cmd.empty()) throw Error(where(rx, context) + ": empty pipe command");
    return run_command_capture(cmd, context);
  }
  std::ifstream in(rx, std::ios::binary);
  if (!in) throw Error(where(rx, context) + ": cannot open: " + std::strerror(errno));
  return read_stream(in);
}

}  // namespace tsrir
