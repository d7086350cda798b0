#include "baselines/ExternalCommand.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>

extern char** environ;

namespace dfrecon {

void runCommand(const std::vector<std::string>& arguments, const std::string& logPath) {
    std::string command;
    for (const std::string& a : arguments) command += (command.empty() ? "" : " ") + a;
    std::vector<char*> argv;
    for (const std::string& a : arguments) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, logPath.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    pid_t pid = 0;
    const int started = ::posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (started != 0)
        throw std::runtime_error("cannot run `" + command + "`: " + std::strerror(started) +
                                 (started == ENOENT ? " (is it installed and on PATH?)" : ""));
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0)
        if (errno != EINTR) throw std::runtime_error("`" + command + "`: waitpid failed");
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return;
    std::ifstream log(logPath);
    std::string output((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
    if (output.size() > 2000) output = "..." + output.substr(output.size() - 2000);
    const std::string how = WIFEXITED(status)
                                ? "exited with " + std::to_string(WEXITSTATUS(status))
                                : "was killed by signal " + std::to_string(WTERMSIG(status));
    throw std::runtime_error("`" + command + "` " + how + ": " + output);
}

}  // namespace dfrecon
