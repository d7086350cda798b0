#include "app/BatchWorkers.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <stdexcept>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/files/JsonText.hpp"
#include "report/ExitCodes.hpp"

extern char** environ;

namespace dfrecon::app {

namespace {

constexpr const char* kWorkerVariable = "DFRECON_BATCH_WORKER";
constexpr const char* kCrashVariable = "DFRECON_BATCH_WORKER_CRASH_ENTRY";

std::vector<std::string>& programArguments() {
    static std::vector<std::string> arguments;
    return arguments;
}

void writeAll(int fd, const std::string& text) {
    for (std::size_t sent = 0; sent < text.size();) {
        const ssize_t n = ::write(fd, text.data() + sent, text.size() - sent);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0)
            throw std::runtime_error("cannot write to a batch worker: " +
                                     std::string(std::strerror(errno)));
        sent += std::size_t(n);
    }
}

// One line from `fd`, without its '\n'; false at the end of the stream
// before a whole line came.
bool readLine(int fd, std::string& line) {
    line.clear();
    char c = 0;
    for (;;) {
        const ssize_t n = ::read(fd, &c, 1);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        if (c == '\n') return true;
        line += c;
    }
}

std::string signalText(int signal) {
    const char* name = strsignal(signal);
    return "signal " + std::to_string(signal) + (name ? " (" + std::string(name) + ")" : "");
}

}  // namespace

void keepProgramArguments(int argc, char** argv) {
    programArguments().assign(argv, argv + argc);
}

bool isBatchWorkerProcess() {
    const char* value = std::getenv(kWorkerVariable);
    return value && std::string(value) == "1";
}

void serveBatchEntries(const std::function<EntryOutcome(std::size_t)>& run,
                       const std::function<std::string(std::size_t)>& idOf) {
    // A worker ends with its batch: killed with it (a scheduler's SIGKILL to
    // the batch alone), it must not finish an entry and record it.
    const pid_t batch = ::getppid();
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != batch) return;  // the batch died before that took hold
    const char* crashId = std::getenv(kCrashVariable);
    std::string line;
    while (std::getline(std::cin, line)) {
        const std::size_t position = std::stoul(line);
        if (crashId && idOf(position) == crashId) {
            std::signal(SIGSEGV, SIG_DFL);  // past any handler a library installed
            std::raise(SIGSEGV);
        }
        const EntryOutcome outcome = run(position);
        std::cout << jsonText(nlohmann::ordered_json{{"status", entryStatusName(outcome.status)},
                                                     {"exitCode", outcome.exitCode},
                                                     {"summary", outcome.summary},
                                                     {"error", outcome.error},
                                                     {"seconds", outcome.seconds}})
                  << "\n"
                  << std::flush;
    }
}

BatchWorker::~BatchWorker() {
    if (toWorker_ >= 0) ::close(toWorker_);
    if (fromWorker_ >= 0) ::close(fromWorker_);
    if (pid_ > 0) {
        int status = 0;
        while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
        }
    }
}

void BatchWorker::start() {
    // Once for the process: a write to a worker that died must fail with
    // EPIPE, not kill the batch.
    static const bool ignoringBrokenPipes = std::signal(SIGPIPE, SIG_IGN) != SIG_ERR;
    (void)ignoringBrokenPipes;
    // Close-on-exec, so that no other worker inherits these ends: a
    // worker's death must close its answer pipe for its parent alone.
    int input[2], output[2];
    if (::pipe2(input, O_CLOEXEC) != 0 || ::pipe2(output, O_CLOEXEC) != 0)
        throw std::runtime_error("cannot start a batch worker: " +
                                 std::string(std::strerror(errno)));
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, input[0], STDIN_FILENO);
    posix_spawn_file_actions_adddup2(&actions, output[1], STDOUT_FILENO);

    std::vector<std::string> environment{std::string(kWorkerVariable) + "=1"};
    for (char** e = environ; *e; ++e)
        if (std::strncmp(*e, kWorkerVariable, std::strlen(kWorkerVariable)) != 0 ||
            (*e)[std::strlen(kWorkerVariable)] != '=')
            environment.emplace_back(*e);
    std::vector<char*> envp, argv;
    for (std::string& e : environment) envp.push_back(e.data());
    envp.push_back(nullptr);
    for (std::string& a : programArguments()) argv.push_back(a.data());
    argv.push_back(nullptr);

    const int error =
        ::posix_spawn(&pid_, "/proc/self/exe", &actions, nullptr, argv.data(), envp.data());
    posix_spawn_file_actions_destroy(&actions);
    ::close(input[0]);
    ::close(output[1]);
    if (error != 0) {
        ::close(input[1]);
        ::close(output[0]);
        pid_ = -1;
        throw std::runtime_error("cannot start a batch worker: " +
                                 std::string(std::strerror(error)));
    }
    toWorker_ = input[1];
    fromWorker_ = output[0];
}

BatchWorker::Result BatchWorker::death() {
    ::close(toWorker_);
    ::close(fromWorker_);
    toWorker_ = fromWorker_ = -1;
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
    pid_ = -1;
    Result result;
    result.died = true;
    EntryOutcome& outcome = result.outcome;
    outcome.status = EntryOutcome::Status::Failed;
    outcome.exitCode = kExitRuntime;
    if (WIFSIGNALED(status)) {
        const int signal = WTERMSIG(status);
        result.lasting = signal == SIGSEGV || signal == SIGBUS || signal == SIGFPE ||
                         signal == SIGILL || signal == SIGABRT;
        outcome.error = "the entry's process ended on " + signalText(signal) +
                        (result.lasting ? " (a defect of dfrecon: please report it with the "
                                          "entry's input)"
                                        : " (killed from outside: out of memory, or a "
                                          "scheduler's limit)");
    } else {
        outcome.error = "the entry's process ended with exit status " +
                        std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) +
                        " before reporting";
    }
    outcome.summary = "failed: " + outcome.error;
    return result;
}

BatchWorker::Result BatchWorker::run(std::size_t position) {
    if (pid_ < 0) start();
    // A worker that died between entries shows here as a write error
    // (EPIPE: the parent ignores SIGPIPE): that is the entry's failure too,
    // and the next entry gets a fresh worker.
    std::string line;
    bool answered = false;
    try {
        writeAll(toWorker_, std::to_string(position) + "\n");
        answered = readLine(fromWorker_, line);
    } catch (const std::runtime_error&) {
        answered = false;
    }
    if (!answered) return death();
    const nlohmann::json answer = parseJsonText(line, "a batch worker's answer", JsonLimits{});
    Result result;
    result.outcome.status = entryStatusNamed(answer.value("status", "failed"));
    result.outcome.exitCode = answer.value("exitCode", int(kExitRuntime));
    result.outcome.summary = answer.value("summary", "");
    result.outcome.error = answer.value("error", "");
    result.outcome.seconds = answer.value("seconds", 0.0);
    return result;
}

}  // namespace dfrecon::app
