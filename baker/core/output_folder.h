// An output folder replaced whole: the new content is built in a sibling folder and swapped in, so
// that the folder is at every instant the old bake or the new one, even when the process is killed
// (kill -9, the OOM killer) at any point; and a lock beside it, so that two bakes never write one
// folder at once (docs/farm.md, "Crash-consistent output").
//
// Names beside FOLDER, in its parent (".NAME" hidden, NAME = FOLDER's last component):
//   .NAME.qf-lock       the lock file, flock()ed while a process owns FOLDER; removed on release
//   .NAME.qf-new-PID    the new content being written by process PID
//   .NAME.qf-old-PID    the old content set aside during a two-rename swap (file systems without
//                       renameat2's RENAME_EXCHANGE, e.g. NFS)
// A sibling exists only while its writer holds the lock, so whoever takes the lock knows every
// sibling it finds is a dead writer's, whatever machine that writer ran on (no PID is trusted);
// and only while the lock file exists (a clean release removes both), so an owner that creates
// the lock file anew has nothing to look for.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

namespace qf {

class OutputFolder {
 public:
  // Takes FOLDER's lock without waiting, creating FOLDER's parent folders if needed, then repairs
  // what a killed writer left (when it finds that writer's lock file): a folder a two-rename swap
  // had set aside is put back (FOLDER missing, ".NAME.qf-old-PID" there), and every
  // ".NAME.qf-new-*" / ".NAME.qf-old-*" is removed.
  // `path` may be relative or a symlink (the folder it leads to is the one replaced).
  // Throws BusyError naming the folder when another process holds the lock; UsageError when `path`
  // is a file, the file system's root, or the current folder or one that holds it (replacing the
  // folder a shell stands in would leave it in a deleted one); OutputError when the parent cannot
  // be written.
  explicit OutputFolder(const std::string& path);
  ~OutputFolder();  // releases the lock (and removes the lock file)
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  const std::string& path() const { return path_; }  // as given (for messages and joined names)

  // Builds the new content and swaps it in for the old. `fill` writes every file into `staging`, a
  // new empty sibling folder (as files written atomically or not: nothing reads it until the swap).
  // Then each entry of the old folder that the new one lacks and for which `keep(name)` is true is
  // hard-linked into it (files a user put beside a bake survive, as they did when files were renamed
  // in one by one), and the new folder replaces the old: one renameat2(RENAME_EXCHANGE) where the
  // file system has it (Linux's local file systems), else two renames (old aside, new in: between
  // them FOLDER is missing for a moment, never mixed, and a kill there is repaired by the next
  // lock). The old content is removed last. If `fill` throws, the sibling is removed and FOLDER is
  // untouched. Throws OutputError when a rename or link is refused.
  void replace(const std::function<void(const std::string& staging)>& fill,
               const std::function<bool(const std::string& name)>& keep);

 private:
  std::filesystem::path sibling(const char* kind, const std::string& pid) const;
  void repair();

  std::string path_;              // as given
  std::filesystem::path folder_;  // absolute, symlinks resolved
  std::filesystem::path lock_path_;
  int lock_ = -1;
  bool clean_ = true;  // no sibling left that the next owner must find (else the lock file stays)
};

}  // namespace qf
