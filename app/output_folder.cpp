#include "app/output_folder.hpp"

#include <H5Cpp.h>
#include <fcntl.h>
#include <mpi.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <random>
#include <regex>
#include <sstream>

#include "fields/hdf5_datasets.hpp"
#include "scene/atomic_file.hpp"

namespace granvv::app {
namespace fs = std::filesystem;

namespace {

const char* const kLockFile = ".granvv.lock";
const char* const kStagingPrefix = ".granvv-staging-";
const char* const kCommitMarker = ".commit";
const char* const kSummary = "summary.json";
const char* const kInterrupted = "interrupted-run";

// The names a run writes into its folder (docs/outputs.md, "The output folder"), and the
// partial files of the writers: a commit removes those of the previous run that the new run
// did not write. Other files in the folder are not touched.
bool is_run_output(const std::string& name) {
  static const std::regex outputs(
      R"((case\.toml|run\.log|results\.h5|summary\.json|report\.html|figures|log\.lammps|)"
      R"(particles(_m[0-9]+)?\.h5|interrupted-run)(\.partial)?)");
  return std::regex_match(name, outputs);
}

std::string quoted(const fs::path& p) {
  return "'" + p.string() + "'";
}

std::string new_run_id() {
  const auto now = std::chrono::system_clock::now().time_since_epoch();
  std::random_device device;
  std::ostringstream id;
  id << std::chrono::duration_cast<std::chrono::milliseconds>(now).count() << "-" << ::getpid()
     << "-" << std::hex << device();
  return id.str();
}

std::vector<std::string> read_lines(const fs::path& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty()) lines.push_back(line);
  }
  return lines;
}

void sync_tree(const fs::path& dir) {
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    if (entry.is_regular_file() || entry.is_directory()) sync_to_disk(entry.path());
  }
  sync_to_disk(dir);
}

// Moves the staged entries named in the commit marker over the previous outputs: summary.json
// goes first (removed) and last (renamed in), so no summary ever sits above data of another
// run. Every step can be repeated, so a commit cut short is finished by running this again.
void finish_commit(const fs::path& target, const fs::path& staging) {
  const std::vector<std::string> staged = read_lines(staging / kCommitMarker);
  const bool summary_staged = fs::exists(staging / kSummary);
  if (summary_staged) fs::remove(target / kSummary);
  for (const auto& name : staged) {
    if (name == kSummary || !fs::exists(fs::symlink_status(staging / name))) continue;
    fs::remove_all(target / name);
    fs::rename(staging / name, target / name);
  }
  for (const auto& entry : fs::directory_iterator(target)) {
    const std::string name = entry.path().filename().string();
    if (is_run_output(name) && std::find(staged.begin(), staged.end(), name) == staged.end()) {
      fs::remove_all(entry.path());
    }
  }
  if (summary_staged) fs::rename(staging / kSummary, target / kSummary);
  sync_to_disk(target);
  fs::remove_all(staging);
}

// Staging folders of runs that died (the caller holds the lock, so no live run owns one): a
// committed one is finished, an unfinished one is removed.
std::vector<std::string> clean_leftovers(const fs::path& dir, bool remove_unfinished) {
  std::vector<std::string> notes;
  std::vector<fs::path> leftovers;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().filename().string().rfind(kStagingPrefix, 0) == 0) {
      leftovers.push_back(entry.path());
    }
  }
  for (const auto& staging : leftovers) {
    const std::string pid = staging.filename().string().substr(std::strlen(kStagingPrefix));
    if (fs::exists(staging / kCommitMarker)) {
      finish_commit(dir, staging);
      notes.push_back("finished replacing the outputs in " + quoted(dir) + " for run pid " + pid +
                      ", which was killed while it replaced them");
    } else if (remove_unfinished) {
      fs::remove_all(staging);
      notes.push_back("removed " + quoted(staging) + ", the unfinished outputs of run pid " + pid +
                      ", which was killed before it completed");
    }
  }
  return notes;
}

fs::path staging_name(const fs::path& dir) {
  return dir / (kStagingPrefix + std::to_string(::getpid()));
}

OutputFolder* g_commit_at_exit = nullptr;

void commit_armed_folder_at_exit() {
  if (!g_commit_at_exit) return;
  try {
    g_commit_at_exit->commit();
  } catch (...) {  // the process is ending: the staging folder stays for the next run
  }
}

}  // namespace

FolderLock::FolderLock(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) {
    throw OutputFolderError("cannot create output folder " + quoted(dir) + ": " + ec.message());
  }
  if (!fs::is_directory(dir, ec)) {
    throw OutputFolderError("output folder " + quoted(dir) + " exists and is not a folder");
  }
  const fs::path lock = dir / kLockFile;
  fd_ = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) {
    throw OutputFolderError("cannot write into output folder " + quoted(dir) + ": " +
                            std::strerror(errno));
  }
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    char pid[32] = {};
    const ssize_t n = ::pread(fd_, pid, sizeof pid - 1, 0);
    ::close(fd_);
    fd_ = -1;
    if (err == EWOULDBLOCK) {
      throw OutputFolderError("another granvv process (pid " +
                              std::string(n > 0 ? pid : "unknown") + ") is writing into " +
                              quoted(dir) + "; wait for it to end or give another --out");
    }
    throw OutputFolderError("cannot lock output folder " + quoted(dir) + ": " + std::strerror(err));
  }
  const std::string pid = std::to_string(::getpid());
  if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, pid.data(), pid.size(), 0) < 0) {
    const int err = errno;
    ::close(fd_);
    fd_ = -1;
    throw OutputFolderError("cannot write into output folder " + quoted(dir) + ": " +
                            std::strerror(err));
  }
}

FolderLock::~FolderLock() {
  if (fd_ >= 0) ::close(fd_);  // releases the flock
}

OutputFolder::OutputFolder(const fs::path& dir)
    : target_(dir), staging_(staging_name(dir)), run_id_(new_run_id()), lock_(dir) {
  try {
    notes_ = clean_leftovers(target_, true);
    fs::remove_all(staging_);  // a folder of an earlier process with our pid
    fs::create_directory(staging_);
  } catch (const fs::filesystem_error& e) {
    throw OutputFolderError("cannot write into output folder " + quoted(dir) + ": " +
                            e.code().message());
  }
}

OutputFolder::~OutputFolder() {
  if (g_commit_at_exit == this) g_commit_at_exit = nullptr;
  if (!done_) {
    std::error_code ec;
    fs::remove_all(staging_, ec);
  }
}

void OutputFolder::commit() {
  if (g_commit_at_exit == this) g_commit_at_exit = nullptr;
  sync_tree(staging_);
  std::string names;
  for (const auto& entry : fs::directory_iterator(staging_)) {
    names += entry.path().filename().string() + "\n";
  }
  write_file_atomically(staging_ / kCommitMarker, names);
  done_ = true;  // from here on the commit is finished by whoever comes next
  finish_commit(target_, staging_);
}

void OutputFolder::keep_as_interrupted() {
  if (g_commit_at_exit == this) g_commit_at_exit = nullptr;
  fs::remove_all(target_ / kInterrupted);
  fs::rename(staging_, target_ / kInterrupted);
  done_ = true;
  sync_to_disk(target_);
}

void OutputFolder::remove_staged_data() {
  static const std::regex data(R"(results\.h5|particles(_m[0-9]+)?\.h5)");
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(staging_, ec)) {
    if (std::regex_match(entry.path().filename().string(), data)) {
      ::truncate(entry.path().c_str(), 0);
      fs::remove(entry.path(), ec);
    }
  }
}

void OutputFolder::abandon() {
  if (g_commit_at_exit == this) g_commit_at_exit = nullptr;
  fs::remove_all(staging_);
  done_ = true;
}

void OutputFolder::commit_at_exit(bool armed) {
  static const bool registered = std::atexit(commit_armed_folder_at_exit) == 0;
  (void)registered;
  g_commit_at_exit = armed ? this : (g_commit_at_exit == this ? nullptr : g_commit_at_exit);
}

std::vector<std::string> finish_interrupted_commits(const fs::path& dir) {
  std::error_code ec;
  bool any = false;  // look before locking: a reader leaves a folder without leftovers as it is
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    any = any || (entry.path().filename().string().rfind(kStagingPrefix, 0) == 0 &&
                  fs::exists(entry.path() / kCommitMarker));
  }
  if (!any) return {};
  try {
    const FolderLock lock(dir);
    return clean_leftovers(dir, false);
  } catch (const OutputFolderError&) {  // a live run holds it, or it is read-only: leave it
    return {};
  }
}

namespace {

bool g_hdf5_broken = false;

}  // namespace

void write_output(const Ranks& ranks, const fs::path& file, const std::function<void()>& write) {
  std::string error;
  if (ranks.writer()) {
    errno = 0;
    const ssize_t open_before = H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_FILE);
    try {
      write();
      // HDF5 reports a close that fails (its last flush, on a full disk) only on stderr, from
      // a destructor: a file left open by the writer is that failure.
      if (H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_FILE) > open_before) {
        const int err = errno;
        error = "cannot write " + file.string() + ": HDF5 could not close it" +
                (err ? " (" + std::string(std::strerror(err)) + ")" : std::string());
        ::truncate(file.c_str(), 0);
        g_hdf5_broken = true;
      }
    } catch (const H5::Exception& e) {
      const int err = errno;
      error = "cannot write " + file.string() + ": " + e.getFuncName() + ": " + e.getDetailMsg();
      if (err == ENOSPC || err == EDQUOT || err == EROFS || err == EIO) {
        error += " (" + std::string(std::strerror(err)) + ")";
      }
      // HDF5 keeps the file open after such a failure; emptying it gives back its space for
      // the summary that reports the failure.
      ::truncate(file.c_str(), 0);
      g_hdf5_broken = true;
    } catch (const std::exception& e) {
      error = "cannot write " + file.string() + ": " + e.what();
    }
    if (!error.empty()) {
      std::error_code ec;
      fs::remove(file, ec);
    }
  }
  if (!all_ranks_ok(ranks, error.empty())) {
    throw std::runtime_error(
        ranks.writer() ? error : "the writer rank failed to write " + file.filename().string());
  }
}

void mark_hdf5_broken() {
  g_hdf5_broken = true;
}

bool hdf5_broken() {
  return g_hdf5_broken;
}

void end_process_now(int exit_code) {
  std::cout.flush();
  std::cerr.flush();
  int initialised = 0, finalised = 0;
  MPI_Initialized(&initialised);
  MPI_Finalized(&finalised);
  if (initialised && !finalised) MPI_Finalize();
  std::_Exit(exit_code);
}

void stamp_run_id(const fs::path& h5_file, const std::string& run_id) {
  H5::Exception::dontPrint();
  H5::H5File h5(h5_file.string(), H5F_ACC_RDWR);
  h5::write_attribute(h5, "run_id", run_id);
}

}  // namespace granvv::app
