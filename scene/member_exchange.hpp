#pragma once
// Ensemble members that ran on other MPI ranks: each member's result and its engine's totals
// sent from the rank that ran it to every rank, in member order, so that every rank reduces
// the same ensemble (rank 0 writes it).
#include <mpi.h>

#include <functional>
#include <vector>

#include "md_bridge/md_run.hpp"

namespace granvv::app {

// A finished member: its run and the totals of the engine that made it (save_state(false)).
struct MemberRecord {
  md::MdRunResult run;
  md::EngineState totals;
};

// Every rank of comm ends with records[m] as rank owner(m) has it (collective; each record is
// broadcast from its owner, members in order). records has one entry per member on every rank.
void share_member_records(std::vector<MemberRecord>& records, const std::function<int(int)>& owner,
                          MPI_Comm comm);

// The record as bytes and back (what share_member_records sends); decode throws
// std::runtime_error for bytes that end early.
std::vector<char> encode_member_record(const MemberRecord& record);
MemberRecord decode_member_record(const std::vector<char>& bytes);

}  // namespace granvv::app
