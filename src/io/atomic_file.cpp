#include "luxtrace/io/atomic_file.hpp"

#include "luxtrace/core/error.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cerrno>
#include <csignal>
#include <cstring>

namespace luxtrace {

namespace fs = std::filesystem;

namespace {

std::string reason(int err) { return std::strerror(err); }

fs::path directory_of(const fs::path& path) { return path.parent_path().empty() ? fs::path(".") : path.parent_path(); }

// ".NAME.tmp." (appended to, not built with "." + name: GCC 12 warns falsely on that,
// -Wrestrict, its bug 105329).
std::string temporary_prefix(const fs::path& path) {
    std::string prefix(1, '.');
    prefix += path.filename().string();
    prefix += ".tmp.";
    return prefix;
}

fs::path temporary_for(const fs::path& path, long pid) {
    return directory_of(path) / (temporary_prefix(path) + std::to_string(pid));
}

// Closes the descriptor and removes the temporary unless released.
class Temporary {
public:
    Temporary(fs::path path, int fd) : path_(std::move(path)), fd_(fd) {}
    ~Temporary() {
        if (fd_ >= 0) ::close(fd_);
        if (!released_) ::unlink(path_.c_str());
    }
    Temporary(const Temporary&) = delete;
    Temporary& operator=(const Temporary&) = delete;
    int fd() const { return fd_; }
    int close() {
        const int r = ::close(fd_);
        fd_ = -1;
        return r;
    }
    void release() { released_ = true; }

private:
    fs::path path_;
    int fd_;
    bool released_ = false;
};

// Temporaries `.NAME.tmp.PID` left beside `path` by writers that died (kill -9, a
// crash) before their rename: removed when their PID is no longer a live process.
// Only that exact pattern for this NAME is touched; returns how many were removed.
int remove_stale_temporaries(const fs::path& path) {
    const std::string prefix = temporary_prefix(path);
    std::error_code ec;
    int removed = 0;
    for (fs::directory_iterator it(directory_of(path), ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
        const std::string digits = name.substr(prefix.size());
        if (digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) continue;
        const long pid = std::stol(digits);
        // ESRCH: no such process. Our own PID's temporary is ours to replace as well.
        const bool dead = pid != ::getpid() && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
        if ((dead || pid == ::getpid()) && it->is_regular_file(ec) && ::unlink(it->path().c_str()) == 0) ++removed;
    }
    return removed;
}

}  // namespace

int write_all(int fd, std::span<const char> bytes) {
    const char* p = bytes.data();
    std::size_t left = bytes.size();
    while (left > 0) {
        const ssize_t n = ::write(fd, p, left);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return errno;
        if (n == 0) return EIO;
        p += n;
        left -= static_cast<std::size_t>(n);
    }
    return 0;
}

void check_writable(const fs::path& path, const std::string& what) {
    remove_stale_temporaries(path);
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && (st.st_mode & 0222) == 0)
        throw IoError(path.string() + ": the " + what +
                      " exists and is read-only; make it writable or choose another path");
    const fs::path probe = temporary_for(path, ::getpid());
    const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0)
        throw IoError(path.string() + ": cannot write the " + what + " in " + directory_of(path).string() + ": " +
                      reason(errno));
    ::close(fd);
    ::unlink(probe.c_str());
}

void write_file_atomically(const fs::path& path, std::span<const char> bytes,
                           const std::function<void()>& before_rename) {
    remove_stale_temporaries(path);
    const fs::path tmp_path = temporary_for(path, ::getpid());
    const int fd = ::open(tmp_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) throw IoError(path.string() + ": cannot create " + tmp_path.string() + ": " + reason(errno));
    Temporary tmp(tmp_path, fd);
    if (const int err = write_all(tmp.fd(), bytes); err != 0)
        throw IoError(path.string() + ": cannot write: " + reason(err));
    // Data on disk before the rename: a crash leaves either the old file or the new one.
    if (::fsync(tmp.fd()) != 0) throw IoError(path.string() + ": cannot write (fsync): " + reason(errno));
    if (tmp.close() != 0) throw IoError(path.string() + ": cannot write (close): " + reason(errno));
    if (before_rename) before_rename();
    if (::rename(tmp_path.c_str(), path.c_str()) != 0)
        throw IoError(path.string() + ": cannot replace the file: " + reason(errno));
    tmp.release();
    const int dfd = ::open(directory_of(path).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dfd >= 0) {
        ::fsync(dfd);
        ::close(dfd);
    }
}

}  // namespace luxtrace
