#include "md_bridge/particle_blocks.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <stdexcept>
#include <string>

namespace granvv::md {
namespace {

constexpr int kPacked = 5;  // id, x, y, v_x, v_y per particle (IDs < 2^53 are exact doubles)

long long block_start(long long n, int ranks, int rank) {
  return n / ranks * rank + n % ranks * rank / ranks;  // floor(rank n / ranks) without overflow
}

int checked_count(long long values, const char* what) {
  if (values > INT_MAX)
    throw std::runtime_error(std::string("particle frame: ") + what + " of " +
                             std::to_string(values) +
                             " values exceeds an MPI count (2^31 - 1); use more ranks");
  return int(values);
}

}  // namespace

IdBlock id_block(long long n, int ranks, int rank) {
  const long long first = block_start(n, ranks, rank);
  return {first, block_start(n, ranks, rank + 1) - first};
}

int id_block_owner(long long row, long long n, int ranks) {
  int k = int(row * double(ranks) / double(n));  // a guess, off by at most one
  k = std::max(0, std::min(ranks - 1, k));
  while (k + 1 < ranks && block_start(n, ranks, k + 1) <= row) ++k;
  while (k > 0 && block_start(n, ranks, k) > row) --k;
  return k;
}

ParticleFrame block_frame(const LocalParticles& local, const std::vector<long long>& ids,
                          long long n, MPI_Comm comm) {
  int ranks = 1, rank = 0;
  MPI_Comm_size(comm, &ranks);
  MPI_Comm_rank(comm, &rank);
  const std::size_t count = std::size_t(local.count);
  if (ids.size() != count)
    throw std::logic_error("particle frame: " + std::to_string(ids.size()) + " IDs for " +
                           std::to_string(count) + " local particles");

  // Packed by destination: counts first, then each particle at its destination's offset.
  std::vector<int> send_counts(std::size_t(ranks), 0), send_offsets(std::size_t(ranks), 0);
  std::vector<int> owner(count);
  bool ids_valid = true;
  for (std::size_t i = 0; i < count; ++i) {
    const long long row = ids[i] - 1;
    if (row < 0 || row >= n) {
      ids_valid = false;
      owner[i] = rank;
      continue;
    }
    owner[i] = id_block_owner(row, n, ranks);
    send_counts[std::size_t(owner[i])] += kPacked;
  }
  // The largest block is the same on every rank, so all refuse it together.
  checked_count(kPacked * (n / ranks + 1), "one rank's block");
  checked_count(kPacked * (long long)count, "one rank's particles");
  for (int k = 1; k < ranks; ++k)
    send_offsets[std::size_t(k)] =
        send_offsets[std::size_t(k - 1)] + send_counts[std::size_t(k - 1)];
  std::vector<double> send(std::size_t(kPacked) * count);
  std::vector<int> fill = send_offsets;
  for (std::size_t i = 0; i < count; ++i) {
    if (ids[i] - 1 < 0 || ids[i] - 1 >= n) continue;
    double* p = &send[std::size_t(fill[std::size_t(owner[i])])];
    fill[std::size_t(owner[i])] += kPacked;
    p[0] = double(ids[i]);
    p[1] = local.x[3 * i];
    p[2] = local.x[3 * i + 1];
    p[3] = local.v[3 * i];
    p[4] = local.v[3 * i + 1];
  }

  std::vector<int> receive_counts(static_cast<std::size_t>(ranks));
  std::vector<int> receive_offsets(static_cast<std::size_t>(ranks), 0);
  MPI_Alltoall(send_counts.data(), 1, MPI_INT, receive_counts.data(), 1, MPI_INT, comm);
  long long received = 0;
  for (int k = 0; k < ranks; ++k) {
    receive_offsets[std::size_t(k)] = int(received);
    received += receive_counts[std::size_t(k)];
  }
  std::vector<double> receive(static_cast<std::size_t>(received));
  MPI_Alltoallv(send.data(), send_counts.data(), send_offsets.data(), MPI_DOUBLE, receive.data(),
                receive_counts.data(), receive_offsets.data(), MPI_DOUBLE, comm);
  send = {};

  const IdBlock block = id_block(n, ranks, rank);
  ParticleFrame frame;
  frame.x.assign(std::size_t(3 * block.count), 0.0);
  frame.v.assign(std::size_t(3 * block.count), 0.0);
  std::vector<char> seen(std::size_t(block.count), 0);
  bool complete = ids_valid && received == kPacked * block.count;
  for (long long j = 0; complete && j < received; j += kPacked) {
    const double* p = &receive[std::size_t(j)];
    const long long row = std::llround(p[0]) - 1 - block.first;
    if (row < 0 || row >= block.count || seen[std::size_t(row)]) {
      complete = false;
      break;
    }
    seen[std::size_t(row)] = 1;
    frame.x[std::size_t(3 * row)] = p[1];
    frame.x[std::size_t(3 * row + 1)] = p[2];
    frame.v[std::size_t(3 * row)] = p[3];
    frame.v[std::size_t(3 * row + 1)] = p[4];
  }
  int all_complete = complete ? 1 : 0;
  MPI_Allreduce(MPI_IN_PLACE, &all_complete, 1, MPI_INT, MPI_MIN, comm);
  if (!all_complete)
    throw std::runtime_error(
        "particle frame: the ranks' particles do not hold each of the IDs 1 .. " +
        std::to_string(n) + " exactly once");
  return frame;
}

}  // namespace granvv::md
