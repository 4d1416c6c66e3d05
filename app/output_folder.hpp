#pragma once
// The output protocol of `granvv run` (docs/outputs.md, "The output protocol"): a run writes
// into a staging folder inside its output folder and replaces the previous outputs only when it
// is complete (or failed with an honest summary), under a lock that keeps a second run out.
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/mpi_ranks.hpp"

namespace granvv::app {

// The output folder cannot be used: it cannot be made or written, or another run holds it.
// `granvv run` and `granvv sweep` exit 2 with this one line.
class OutputFolderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An exclusive lock on a folder (flock on DIR/.granvv.lock, holding the owner's pid), held
// until destruction. Throws OutputFolderError if the folder cannot be made or written, or if
// another live process holds the lock.
class FolderLock {
 public:
  explicit FolderLock(const std::filesystem::path& dir);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  int fd_ = -1;
};

class OutputFolder {
 public:
  // Makes dir, takes its lock, finishes or removes what a killed run left there (each action is
  // one line of notes()) and makes an empty staging folder DIR/.granvv-staging-<pid>.
  explicit OutputFolder(const std::filesystem::path& dir);
  // Removes the staging folder unless it was committed or kept; releases the lock.
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  const std::filesystem::path& target() const { return target_; }
  const std::filesystem::path& staging() const { return staging_; }
  // Unique per run; stamped into summary.json and results.h5 so that a reader can tell that
  // both belong to the same run.
  const std::string& run_id() const { return run_id_; }
  const std::vector<std::string>& notes() const { return notes_; }

  // Flushes every staged file to the disk, then moves them over the previous outputs, with
  // summary.json removed first and put in place last. A kill during the move leaves a commit
  // marker that the next run (or `granvv report`) uses to finish it. Throws std::runtime_error.
  void commit();
  // True once commit() has written its marker (the replacement is then finished by whoever
  // comes next, if this process cannot).
  bool commit_begun() const { return done_; }
  // Keeps the previous outputs and moves the staging folder to DIR/interrupted-run.
  void keep_as_interrupted();
  // Removes results.h5 and the particle files from the staging folder (emptied first, so that
  // their space comes back even if a writer still holds them open).
  void remove_staged_data();
  // Removes the staging folder (nothing of this run is kept).
  void abandon();

  // While armed, a process that ends through exit() (the Debian LAMMPS does that on an error,
  // docs/physics.md §10) commits the staging folder as it is: its summary.json then already
  // says "failed" with the reason.
  void commit_at_exit(bool armed);

 private:
  std::filesystem::path target_, staging_;
  std::string run_id_;
  std::vector<std::string> notes_;
  FolderLock lock_;
  bool done_ = false;
};

// Finishes the commits that a killed run left half done in dir (the staging folders with a
// commit marker); returns one line per folder finished. Used by `granvv report`.
std::vector<std::string> finish_interrupted_commits(const std::filesystem::path& dir);

// Runs write (which makes or extends file) on the writer rank. If it fails, file is removed (a
// half-written HDF5 file is unreadable) and every rank throws std::runtime_error naming file and
// the reason, HDF5 errors included, so that all ranks take the failure path together.
void write_output(const Ranks& ranks, const std::filesystem::path& file,
                  const std::function<void()>& write);

// After a failed HDF5 write (a full disk) the HDF5 library of Debian (1.10) holds a file it can
// neither close nor forget: closing it again, as it does at program exit, crashes. The failure is
// marked (write_output marks it; mark_hdf5_broken for writes made elsewhere), and the command
// ends the process with end_process_now once its outputs are complete, which skips the
// library's exit handlers (MPI is finalised first).
void mark_hdf5_broken();
bool hdf5_broken();
[[noreturn]] void end_process_now(int exit_code);

// Writes the string attribute run_id at the root of an existing HDF5 file.
void stamp_run_id(const std::filesystem::path& h5_file, const std::string& run_id);

}  // namespace granvv::app
