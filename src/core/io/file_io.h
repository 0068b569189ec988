#pragma once
// Whole-file reads and atomic writes. A write goes to a temporary file beside the target
// that is renamed over it only when complete, so a failed or interrupted command never
// leaves a half-written output, and an existing output survives a failure untouched.

#include <cstdint>
#include <string>
#include <vector>

#include "core/result.h"

namespace btflut {

using Bytes = std::vector<std::uint8_t>;

/// Reads a whole file; errors name the file ("PATH: no such file", ...).
Result<Bytes> readFile(const std::string& path);

/// Writes bytes to `path` through a temporary file and a rename. The temporary file is
/// created exclusively under a random name beside `path` (nothing planted there is
/// followed) and removed on failure. Folders of `path` that do not exist are made.
Status writeFileAtomically(const std::string& path, const void* data, std::size_t size);

/// One output of writeFilesAtomically.
struct FileContents {
    std::string path;
    const void* data;
    std::size_t size;
};

/// Writes several files that belong together: all are complete in temporary files before
/// the first is renamed into place, so a failure leaves every old output as it was.
Status writeFilesAtomically(const std::vector<FileContents>& files);
inline Status writeFileAtomically(const std::string& path, const Bytes& bytes) {
    return writeFileAtomically(path, bytes.data(), bytes.size());
}
inline Status writeFileAtomically(const std::string& path, const std::string& text) {
    return writeFileAtomically(path, text.data(), text.size());
}

/// Lower-case extension without the dot ("png" for "a/b.PNG"), empty if none.
std::string fileExtension(const std::string& path);

}  // namespace btflut
