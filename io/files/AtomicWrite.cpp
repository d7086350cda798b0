#include "io/files/AtomicWrite.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <stdexcept>
#include <vector>

#include "io/files/OutputTarget.hpp"

namespace dfrecon {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what, int error = 0) {
    throw std::runtime_error("cannot write " + path + ": " + what +
                             (error ? std::string(": ") + std::strerror(error) : ""));
}

// ---- Cleanup on signals -------------------------------------------------
// The private folders of writes under way, in fixed storage a signal handler
// may read: a slot is filled first and published by its state.

constexpr std::size_t kSlots = 64, kPathBytes = 4096;
constexpr int kFree = 0, kClaimed = 1, kActive = 2;

struct Slot {
    std::atomic<int> state{kFree};
    char folder[kPathBytes], link[kPathBytes], data[kPathBytes];
};
std::array<Slot, kSlots> slots;
constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};

void removeActiveStages() {
    for (Slot& slot : slots)
        if (slot.state.load() == kActive) {
            ::unlink(slot.data);
            ::unlink(slot.link);
            ::rmdir(slot.folder);
        }
}

extern "C" void onTerminatingSignal(int signal) {
    removeActiveStages();
    // Die of the signal as if unhandled, so the parent sees what happened.
    std::signal(signal, SIG_DFL);
    std::raise(signal);
}

void installSignalCleanup() {
    static std::once_flag installed;
    std::call_once(installed, [] {
        for (int signal : kSignals) {
            struct sigaction previous {};
            if (::sigaction(signal, nullptr, &previous) != 0) continue;
            // Respect an ignored signal (nohup) and a handler someone else set.
            if (previous.sa_handler != SIG_DFL) continue;
            struct sigaction action {};
            action.sa_handler = onTerminatingSignal;
            sigemptyset(&action.sa_mask);
            for (int other : kSignals) sigaddset(&action.sa_mask, other);
            ::sigaction(signal, &action, nullptr);
        }
    });
}

// ---- One write ------------------------------------------------------------

/// The private folder, the memfd and the link to it, for one write; removes
/// them all when destroyed.
class Stage {
  public:
    explicit Stage(const std::string& path) : path_(path) {
        installSignalCleanup();
        try {
            create();
        } catch (...) {
            remove();
            throw;
        }
    }
    ~Stage() { remove(); }
    Stage(const Stage&) = delete;
    Stage& operator=(const Stage&) = delete;

    /// Where the library writes.
    const std::string& stagePath() const { return link_; }

    /// Copies what was written into a new file with checked writes, fsyncs
    /// and closes it, renames it to the target and syncs the folder.
    void commit() {
        const int source = openWritten();
        const int out =
            ::open(data_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
        if (out < 0) {
            if (source != memory_) ::close(source);
            fail(path_, "cannot create the file", errno);
        }
        const int copyError = copyAll(source, out);
        if (source != memory_) ::close(source);
        const int syncError = copyError ? 0 : (::fsync(out) == 0 ? 0 : errno);
        const int closeError = ::close(out) == 0 ? 0 : errno;
        if (copyError || syncError || closeError)
            fail(path_, "write failed", copyError ? copyError : syncError ? syncError : closeError);
        if (::rename(data_.c_str(), path_.c_str()) != 0) fail(path_, "cannot rename", errno);
        syncFolder();
    }

  private:
    void create() {
        const std::string& path = path_;
        const fs::path target(path);
        const fs::path parent = target.parent_path().empty() ? fs::path(".") : target.parent_path();
        const std::string name = target.filename().string();
        if (name.empty() || name == "." || name == "..") fail(path, "not a file name");
        std::string pattern = (parent / ("." + name + ".dfrecon-XXXXXX")).string();
        if (pattern.size() + name.size() + 8 >= kPathBytes) fail(path, "path too long");
        if (!::mkdtemp(pattern.data())) fail(path, "cannot create a temporary folder", errno);
        folder_ = pattern;
        link_ = (fs::path(folder_) / name).string();
        data_ = (fs::path(folder_) / ("." + name + ".part")).string();  // never the link's name
        claimSlot();
        memory_ = ::memfd_create("dfrecon-output", MFD_CLOEXEC);
        if (memory_ < 0) fail(path, "cannot create an in-memory file", errno);
        const std::string proc = "/proc/self/fd/" + std::to_string(memory_);
        if (::symlink(proc.c_str(), link_.c_str()) != 0)
            fail(path, "cannot create a temporary link", errno);
    }

    void remove() {
        if (memory_ >= 0) ::close(memory_);
        memory_ = -1;
        if (!folder_.empty()) {
            ::unlink(data_.c_str());
            ::unlink(link_.c_str());
            ::rmdir(folder_.c_str());
        }
        if (slot_) slot_->state.store(kFree);
        slot_ = nullptr;
    }

    void claimSlot() {
        for (Slot& slot : slots) {
            int expected = kFree;
            if (!slot.state.compare_exchange_strong(expected, kClaimed)) continue;
            std::strncpy(slot.folder, folder_.c_str(), kPathBytes - 1);
            std::strncpy(slot.link, link_.c_str(), kPathBytes - 1);
            std::strncpy(slot.data, data_.c_str(), kPathBytes - 1);
            slot.state.store(kActive);
            slot_ = &slot;
            return;
        }
        // More writes at once than slots: still correct, only a signal during
        // this one would leave its folder behind.
    }

    /// The bytes written: the memfd, unless the library replaced our link
    /// with a file of its own (some unlink before creating).
    int openWritten() {
        struct stat info {};
        if (::lstat(link_.c_str(), &info) != 0) fail(path_, "the output was removed", errno);
        if (S_ISLNK(info.st_mode)) {
            checkBelowSizeLimit(memory_);
            if (::lseek(memory_, 0, SEEK_SET) != 0) fail(path_, "cannot read back", errno);
            return memory_;
        }
        if (!S_ISREG(info.st_mode)) fail(path_, "the output is not a regular file");
        const int fd = ::open(link_.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
        if (fd < 0) fail(path_, "cannot read back", errno);
        return fd;
    }

    /// The one way the memfd can refuse bytes: a file size limit (ulimit -f),
    /// which a library that ignores its write errors would not tell us of.
    /// A staged file that reached the limit is taken as cut short.
    void checkBelowSizeLimit(int fd) const {
        struct rlimit limit {};
        struct stat info {};
        if (::getrlimit(RLIMIT_FSIZE, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return;
        if (::fstat(fd, &info) == 0 && rlim_t(info.st_size) >= limit.rlim_cur)
            fail(path_, "output reached the file size limit (ulimit -f)", EFBIG);
    }

    /// 0, or the errno of the failing read or write.
    static int copyAll(int from, int to) {
        std::vector<char> buffer(1 << 20);
        for (;;) {
            const ssize_t got = ::read(from, buffer.data(), buffer.size());
            if (got < 0) {
                if (errno == EINTR) continue;
                return errno;
            }
            if (got == 0) return 0;
            for (ssize_t done = 0; done < got;) {
                const ssize_t put = ::write(to, buffer.data() + done, std::size_t(got - done));
                if (put < 0) {
                    if (errno == EINTR) continue;
                    return errno;
                }
                if (put == 0) return EIO;
                done += put;
            }
        }
    }

    void syncFolder() const {
        // The rename itself is durable only once the folder is; a folder
        // that cannot be synced (some network filesystems) is not an error.
        const fs::path parent = fs::path(path_).parent_path();
        const int dir =
            ::open(parent.empty() ? "." : parent.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
        if (dir < 0) return;
        ::fsync(dir);
        ::close(dir);
    }

    std::string path_, folder_, link_, data_;
    int memory_ = -1;
    Slot* slot_ = nullptr;
};

}  // namespace

void writeAtomically(const std::string& path,
                     const std::function<bool(const std::string&)>& write) {
    // "-" is standard output on the command line (docs/cli.md): an output
    // that reaches here with it cannot stream, and a file named "-" is never
    // what was meant.
    if (path == "-")
        throw std::invalid_argument("this output cannot go to standard output ('-'): give a file");
    checkOutputTarget(path);
    Stage stage(path);
    if (!write(stage.stagePath())) fail(path, "the writer failed");
    stage.commit();
    noteOutputWritten(path);
}

void writeStreamAtomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write) {
    writeAtomically(path, [&](const std::string& staged) {
        std::ofstream out(staged, std::ios::binary | std::ios::trunc);
        if (!out) fail(path, "cannot open", errno);
        write(out);
        out.flush();
        if (!out) fail(path, "write failed");
        return true;
    });
}

}  // namespace dfrecon
