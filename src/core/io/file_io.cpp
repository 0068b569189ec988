#include "core/io/file_io.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace btflut {

namespace {

// The process's umask, read once (umask can only be read by setting it).
mode_t processUmask() {
    static const mode_t mask = [] {
        mode_t m = ::umask(022);
        ::umask(m);
        return m;
    }();
    return mask;
}

bool writeAll(int fd, const std::uint8_t* data, std::size_t size) {
    while (size > 0) {
        const ssize_t n = ::write(fd, data, size);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        data += n;
        size -= static_cast<std::size_t>(n);
    }
    return true;
}

// A new temporary file beside `path`, created exclusively (mkstemp: O_CREAT | O_EXCL with
// a random name), so nothing planted at a predictable name (a symlink, say) is followed.
struct TempFile {
    std::string name;
    int fd = -1;
};

Result<TempFile> createTempBeside(const std::string& path) {
    std::string pattern = path + ".tmp.XXXXXX";
    const int fd = ::mkstemp(pattern.data());
    if (fd < 0) return Error{path + ": cannot write (" + std::strerror(errno) + ")"};
    // mkstemp makes the file 0600; give it the mode an ordinary new file would get.
    ::fchmod(fd, 0666 & ~processUmask());
    return TempFile{pattern, fd};
}

}  // namespace

Result<Bytes> readFile(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) return Error{path + ": is a directory, expected a file"};
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) return Error{path + ": cannot open (" + std::strerror(errno) + ")"};
    Bytes bytes;
    std::uint8_t buffer[1 << 16];
    std::size_t n;
    while ((n = std::fread(buffer, 1, sizeof buffer, f)) > 0) bytes.insert(bytes.end(), buffer, buffer + n);
    bool failed = std::ferror(f);
    std::fclose(f);
    if (failed) return Error{path + ": read error"};
    return bytes;
}

Status writeFilesAtomically(const std::vector<FileContents>& files) {
    std::vector<std::string> temps;
    auto discard = [&] {
        for (const std::string& t : temps) std::remove(t.c_str());
    };
    for (const FileContents& file : files) {
        // A folder the path names but that does not exist yet is made (-o new/x.png).
        const std::filesystem::path parent = std::filesystem::path(file.path).parent_path();
        std::error_code ec;
        if (!parent.empty() && !std::filesystem::is_directory(parent, ec)) {
            std::filesystem::create_directories(parent, ec);
            if (ec) {
                discard();
                return Error{file.path + ": cannot create the folder " + parent.string() + " (" + ec.message() + ")"};
            }
        }
        Result<TempFile> tmp = createTempBeside(file.path);
        if (!tmp) {
            discard();
            return Error{tmp.error()};
        }
        temps.push_back(tmp->name);
        const auto* bytes = static_cast<const std::uint8_t*>(file.data);
        bool ok = writeAll(tmp->fd, bytes, file.size);
        ok = (::close(tmp->fd) == 0) && ok;
        if (!ok) {
            const std::string reason = std::strerror(errno);
            discard();
            return Error{file.path + ": cannot write (" + reason + ")"};
        }
    }
    // Every file is complete before the first rename.
    for (std::size_t i = 0; i < files.size(); ++i) {
        if (std::rename(temps[i].c_str(), files[i].path.c_str()) != 0) {
            const std::string reason = std::strerror(errno);
            temps.erase(temps.begin(), temps.begin() + static_cast<std::ptrdiff_t>(i));
            discard();
            return Error{files[i].path + ": cannot write (" + reason + ")"};
        }
    }
    return success();
}

Status writeFileAtomically(const std::string& path, const void* data, std::size_t size) {
    return writeFilesAtomically({{path, data, size}});
}

std::string fileExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    if (!ext.empty()) ext.erase(0, 1);
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

}  // namespace btflut
