#include "io/rxfile.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
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

void read_stream(std::istream& in, const ByteSink& sink) {
  std::vector<char> buf(1 << 16);
  while (in.read(buf.data(), static_cast<std::streamsize>(buf.size())) || in.gcount() > 0) {
    sink(buf.data(), static_cast<size_t>(in.gcount()));
  }
}

ByteSink append_to(std::vector<char>& data) {
  return [&data](const char* p, size_t n) { data.insert(data.end(), p, p + n); };
}

}  // namespace

bool is_pipe_rxfilename(const std::string& rx) {
  std::string t = trim(rx);
  return !t.empty() && t.back() == '|';
}

std::vector<char> run_command_capture(const std::string& command, const std::string& context) {
  std::vector<char> out;
  run_command_stream(command, append_to(out), context);
  return out;
}

void run_command_stream(const std::string& command, const ByteSink& sink, const std::string& context) {
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
        if (f.fd == out_pipe[0]) {
          try {
            sink(buf, static_cast<size_t>(n));
          } catch (...) {
            // The sink gave up (e.g. disk full): stop the command and reap it, then report.
            kill(pid, SIGTERM);
            for (auto& g : fds) {
              if (g.fd >= 0) close(g.fd);
            }
            int ignored = 0;
            while (waitpid(pid, &ignored, 0) < 0 && errno == EINTR) {
            }
            throw;
          }
        }
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
}

void stream_rxfile(const std::string& rx, const ByteSink& sink, const std::string& context) {
  std::string t = trim(rx);
  if (t.empty()) throw Error((context.empty() ? std::string("") : context + ": ") + "empty file name");
  if (t == "-") return read_stream(std::cin, sink);
  if (t.back() == '|') {
    std::string cmd = trim(t.substr(0, t.size() - 1));
    if (cmd.empty()) throw Error(where(rx, context) + ": empty pipe command");
    return run_command_stream(cmd, sink, context);
  }
  std::ifstream in(rx, std::ios::binary);
  if (!in) throw Error(where(rx, context) + ": cannot open: " + std::strerror(errno));
  read_stream(in, sink);
}

std::vector<char> read_rxfile(const std::string& rx, const std::string& context) {
  std::vector<char> data;
  stream_rxfile(rx, append_to(data), context);
  return data;
}

}  // namespace tsrir
