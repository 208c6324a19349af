// fork/execvp with three pipes and a poll() loop: stdin is written as the
// child reads it, stdout and stderr are drained as they fill (a child that
// writes a lot never blocks on a full pipe), and at the deadline the child is
// killed with SIGKILL. SIGPIPE is ignored by the fuzzer (a child may exit
// before reading all of its input) and restored to its default in the child.
#include "child.hpp"

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <fcntl.h>
#include <poll.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace impactgen::fuzz {

namespace {

void close_fd(int& fd)
{
    if (fd >= 0)
        ::close(fd);
    fd = -1;
}

// In the child, between fork and exec: only async-signal-safe calls.
[[noreturn]] void exec_child(const std::vector<char*>& args, int in, int out, int err, std::size_t memory_mb)
{
    ::dup2(in, 0);
    ::dup2(out, 1);
    ::dup2(err, 2);
    ::signal(SIGPIPE, SIG_DFL);
    if (memory_mb > 0) {
        rlimit lim{};
        lim.rlim_cur = lim.rlim_max = static_cast<rlim_t>(memory_mb) << 20;
        ::setrlimit(RLIMIT_AS, &lim);
    }
    ::execvp(args[0], args.data());
    const char msg[] = "fuzz_cli: exec failed\n";
    ssize_t ignored = ::write(2, msg, sizeof msg - 1);
    (void)ignored;
    ::_exit(127);
}

// Appends what is readable on fd to text (up to cap); false at end of file.
bool drain(int fd, std::string& text, bool& cut, std::size_t cap)
{
    char buf[65536];
    for (;;) {
        ssize_t n = ::read(fd, buf, sizeof buf);
        if (n > 0) {
            std::size_t room = text.size() < cap ? cap - text.size() : 0;
            std::size_t keep = std::min(room, static_cast<std::size_t>(n));
            text.append(buf, keep);
            cut = cut || keep < static_cast<std::size_t>(n);
            continue;
        }
        if (n == 0)
            return false;
        if (errno == EINTR)
            continue;
        return errno == EAGAIN || errno == EWOULDBLOCK;
    }
}

} // namespace

run_result run_child(const std::vector<std::string>& argv, const std::string& input, const run_limits& limits)
{
    static const bool sigpipe_ignored = [] {
        ::signal(SIGPIPE, SIG_IGN);
        return true;
    }();
    (void)sigpipe_ignored;

    run_result r;
    int in[2], out[2], err[2];
    if (::pipe2(in, O_CLOEXEC) != 0 || ::pipe2(out, O_CLOEXEC) != 0 || ::pipe2(err, O_CLOEXEC) != 0) {
        r.err = std::string("fuzz_cli: pipe: ") + std::strerror(errno);
        r.exit_code = 127;
        return r;
    }
    std::vector<char*> args;
    for (const std::string& a : argv)
        args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);

    const auto start = std::chrono::steady_clock::now();
    pid_t pid = ::fork();
    if (pid == 0)
        exec_child(args, in[0], out[1], err[1], limits.memory_mb);
    ::close(in[0]);
    ::close(out[1]);
    ::close(err[1]);
    int to_child = in[1], from_out = out[0], from_err = err[0];
    if (pid < 0) {
        close_fd(to_child);
        close_fd(from_out);
        close_fd(from_err);
        r.err = std::string("fuzz_cli: fork: ") + std::strerror(errno);
        r.exit_code = 127;
        return r;
    }
    for (int fd : {to_child, from_out, from_err})
        ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) | O_NONBLOCK);
    std::size_t written = 0;
    if (input.empty())
        close_fd(to_child);

    const auto deadline = start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                      std::chrono::duration<double>(limits.timeout_seconds));
    while (from_out >= 0 || from_err >= 0) {
        auto now = std::chrono::steady_clock::now();
        if (now >= deadline) {
            r.timed_out = true;
            ::kill(pid, SIGKILL);
            break;
        }
        auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - now).count() + 1;
        pollfd fds[3];
        nfds_t n = 0;
        for (int fd : {from_out, from_err})
            if (fd >= 0)
                fds[n++] = {fd, POLLIN, 0};
        if (to_child >= 0)
            fds[n++] = {to_child, POLLOUT, 0};
        int ready = ::poll(fds, n, static_cast<int>(std::min<long long>(left, 1000)));
        if (ready < 0 && errno != EINTR)
            break;
        if (ready <= 0)
            continue;
        for (nfds_t k = 0; k < n; ++k) {
            if (fds[k].revents == 0)
                continue;
            if (fds[k].fd == to_child) {
                ssize_t w = ::write(to_child, input.data() + written, input.size() - written);
                if (w > 0)
                    written += static_cast<std::size_t>(w);
                if ((w < 0 && errno != EAGAIN && errno != EINTR) || written == input.size())
                    close_fd(to_child);
            } else if (fds[k].fd == from_out) {
                if (!drain(from_out, r.out, r.out_cut, limits.output_cap))
                    close_fd(from_out);
            } else if (!drain(from_err, r.err, r.err_cut, limits.output_cap)) {
                close_fd(from_err);
            }
        }
    }
    close_fd(to_child);
    close_fd(from_out);
    close_fd(from_err);
    // The pipes are closed when the child exits, or when it closed them itself
    // and goes on: the deadline still holds.
    int status = 0;
    for (;;) {
        pid_t done = ::waitpid(pid, &status, r.timed_out ? 0 : WNOHANG);
        if (done == pid || (done < 0 && errno != EINTR))
            break;
        if (done == 0 && std::chrono::steady_clock::now() >= deadline) {
            r.timed_out = true;
            ::kill(pid, SIGKILL);
        } else if (done == 0) {
            ::usleep(1000);
        }
    }
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (r.timed_out)
        return r;
    if (WIFSIGNALED(status))
        r.signal = WTERMSIG(status);
    else if (WIFEXITED(status))
        r.exit_code = WEXITSTATUS(status);
    return r;
}

} // namespace impactgen::fuzz
