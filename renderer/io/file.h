// Files: every file octrace reads (scenes, images) and writes (images,
// scenes, CSVs) goes through here. Writing is atomic, so that a failed or
// interrupted run never leaves a truncated file.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace octrace {

// Writes `size` bytes to a temporary file beside `path`, flushes it to disk and
// renames it over `path` (atomic on POSIX): `path` holds either its old
// contents or the complete new ones. The file gets the usual permissions
// (0666 & ~umask). On failure the temporary is removed and RuntimeError
// "PATH: WHAT: reason" is thrown (WHAT e.g. "cannot write image").
void write_file_atomically(const std::string& path, const void* data, size_t size,
                           const std::string& what = "cannot write");

// Several files that belong together (a state's .accum, .mean.pfm and
// .count.pfm): every one is written to its temporary and flushed before
// any is renamed, so that a failure while writing leaves none of them new
// (each keeps its old contents). A second Ctrl-C removes the temporaries
// of the first 8 files of a set (remove_file_being_written).
struct FileToWrite {
  std::string path;
  const void* data;
  size_t size;
  std::string what = "cannot write";
};
void write_files_atomically(const std::vector<FileToWrite>& files);

// Removes the temporary files that write_file(s)_atomically is writing at
// this moment, if any: async-signal-safe, for a handler that ends the
// process at once (a second Ctrl-C), so that no partial file is left behind.
void remove_file_being_written() noexcept;

// The whole file. Throws InputError "PATH: cannot open file: reason" (or
// "cannot read file").
std::string read_file(const std::string& path);

// Checks, before any long work, that `path` can be written: its folder exists,
// it is not a folder itself, and a file can be made beside it (which is then
// removed). Throws InputError "PATH: folder does not exist" / "PATH: is a
// folder, not a file" / "PATH: cannot write in its folder: reason".
void check_output_folder(const std::string& path);

}  // namespace octrace
