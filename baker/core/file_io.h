// Whole-file reads and atomic writes (write to a temporary name in the same folder, then rename),
// so that no reader ever sees a half-written output, even if the process is killed.
#pragma once

#include <cstdint>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace qf {

// Reads the whole file. Throws InputError("file.unreadable") if it cannot be opened or read.
std::vector<std::uint8_t> read_file_bytes(const std::string& path);

// Calls `write` with a stream on "<path>.tmp-<pid>" next to `path`, flushes, fsyncs and renames
// it over `path`. If `write` throws, or the stream fails, the temporary file is removed and the
// exception propagates; `path` is left untouched.
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write);

// Lower-case extension without the dot ("ply" for "a/b.PLY"), or "" if none.
std::string file_extension(const std::string& path);

}  // namespace qf
