// References confined to the asset's folder (asset_files.h).
#include "io/asset_files.h"

#include <sys/stat.h>

#include <deque>
#include <system_error>

#include "core/error.h"

namespace qf::io {

namespace fs = std::filesystem;

std::string percent_decoded(const std::string& uri) {
  const auto hex = [](char c) { return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1; };
  std::string out;
  for (std::size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && hex(uri[i + 1]) >= 0 && hex(uri[i + 2]) >= 0) {
      out += static_cast<char>(hex(uri[i + 1]) * 16 + hex(uri[i + 2]));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

fs::path asset_root(const std::string& model_path, const std::string& root_option) {
  const fs::path folder = root_option.empty() ? fs::path(model_path).parent_path() : fs::path(root_option);
  std::error_code ec;
  fs::path root = fs::weakly_canonical(fs::absolute(folder.empty() ? fs::path(".") : folder, ec), ec);
  return ec ? fs::absolute(folder).lexically_normal() : root;
}

namespace {

void push_front_parts(std::deque<fs::path>& todo, const fs::path& relative) {
  std::deque<fs::path> parts(relative.begin(), relative.end());
  todo.insert(todo.begin(), parts.begin(), parts.end());
}

}  // namespace

std::optional<fs::path> resolve_inside(const fs::path& root, const fs::path& base_folder, const std::string& reference) {
  // A component at a time from the root, as the kernel walks a path, but never stepping outside
  // it: `here` is always inside the root with no symlink in it; each symlink met is read
  // (readlink, not followed) and its target walked the same way; 40 symlinks at most, as Linux
  // allows. The reference's own parts are not normalised first: "link/../x" goes where the kernel
  // would take it, through link's target.
  // A NUL ("%00") would cut the path the kernel sees short of the one walked here.
  if (reference.empty() || reference.find('\0') != std::string::npos) return std::nullopt;
  const fs::path ref(reference);
  std::error_code ec;
  const fs::path from = ref.is_absolute() ? ref : fs::weakly_canonical(fs::absolute(base_folder, ec), ec) / ref;
  if (ec) return std::nullopt;
  std::deque<fs::path> todo(from.begin(), from.end());
  for (const fs::path& r : root) {
    if (r.empty()) continue;
    if (todo.empty() || todo.front() != r) return std::nullopt;  // not below the root
    todo.pop_front();
  }
  fs::path here = root;
  int links = 0;
  while (!todo.empty()) {
    const fs::path part = todo.front();
    todo.pop_front();
    if (part.empty() || part == ".") continue;
    if (part == "..") {
      if (here == root) return std::nullopt;
      here = here.parent_path();
      continue;
    }
    const fs::path next = here / part;
    const fs::file_status st = fs::symlink_status(next, ec);
    if (ec || !fs::is_symlink(st)) {
      here = next;  // a file, a folder or nothing yet: taken as it is
      continue;
    }
    if (++links > 40) return std::nullopt;
    const fs::path target = fs::read_symlink(next, ec);
    if (ec || target.empty()) return std::nullopt;
    if (target.is_absolute()) {
      std::deque<fs::path> parts(target.begin(), target.end());
      for (const fs::path& r : root) {
        if (r.empty()) continue;
        if (parts.empty() || parts.front() != r) return std::nullopt;
        parts.pop_front();
      }
      here = root;
      todo.insert(todo.begin(), parts.begin(), parts.end());
    } else {
      push_front_parts(todo, target);
    }
  }
  return here;
}

fs::path confined_file(const fs::path& root, const fs::path& base_folder, const std::string& reference, const std::string& written,
                       const std::string& file, const std::string& prefix, const std::string& where) {
  const std::optional<fs::path> found = resolve_inside(root, base_folder, reference);
  if (!found)
    throw InputError(prefix + ".outside_asset", file, where,
                     "'" + written + "' leads outside the asset's folder " + root.string() +
                         ": refused (an asset reads only the files in its folder; --asset-root DIR widens it)");
  struct stat st {};
  if (::stat(found->c_str(), &st) == 0 && !S_ISREG(st.st_mode))
    throw InputError(prefix + ".not_regular_file", file, where,
                     "'" + written + "' names " + (S_ISDIR(st.st_mode) ? "a folder" : S_ISFIFO(st.st_mode) ? "a FIFO" : "a device or socket") +
                         ", not a regular file");
  return *found;
}

}  // namespace qf::io
