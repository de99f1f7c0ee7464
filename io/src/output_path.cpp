#include "pliant/io/output_path.h"

#include <unistd.h>

#include <filesystem>

#include "pliant/io/input_error.h"

namespace pliant::io {
namespace {

namespace fs = std::filesystem;

// The directory that will hold a new entry named `path`.
fs::path Parent(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? fs::path(".") : parent;
}

void CheckWritableDirectory(const fs::path& directory, const std::string& option,
                            const std::string& path) {
  std::error_code error;
  const std::string name = directory.string();
  if (!fs::exists(directory, error)) {
    throw InputError(option + " " + path, 0, 0, "the directory " + name + " does not exist",
                     "create it first (mkdir -p " + name + ") or write elsewhere");
  }
  if (!fs::is_directory(directory, error)) {
    throw InputError(option + " " + path, 0, 0, name + " is not a directory",
                     "give a path inside a directory");
  }
  if (::access(name.c_str(), W_OK | X_OK) != 0) {
    throw InputError(option + " " + path, 0, 0, "the directory " + name + " is not writable",
                     "write into a directory you may write to, or change its permissions");
  }
}

}  // namespace

void CheckOutputFile(const std::string& path, const std::string& option) {
  if (path.empty() || path == "-") return;  // standard output
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  // A FIFO or a device (/dev/null) is written through, never replaced: its
  // directory need not be writable (atomic_file.h).
  if (fs::is_fifo(status) || fs::is_character_file(status)) return;
  if (fs::is_directory(path, error)) {
    throw InputError(option + " " + path, 0, 0, "is a directory",
                     "give a file name (e.g. " + (fs::path(path) / "out").string() + ")");
  }
  CheckWritableDirectory(Parent(path), option, path);
}

void CheckOutputDirectory(const std::string& path, const std::string& option) {
  if (path.empty()) return;
  std::error_code error;
  if (fs::exists(path, error)) {
    if (!fs::is_directory(path, error)) {
      throw InputError(option + " " + path, 0, 0, "is a file, and this output is a directory",
                       "give a directory name (it is created if missing)");
    }
    CheckWritableDirectory(path, option, path);
    return;
  }
  // Created with its missing parents: the nearest existing ancestor must take them.
  fs::path ancestor = fs::absolute(fs::path(path), error).parent_path();
  while (!ancestor.empty() && !fs::exists(ancestor, error) && ancestor != ancestor.root_path()) {
    ancestor = ancestor.parent_path();
  }
  CheckWritableDirectory(ancestor, option, path);
}

}  // namespace pliant::io
