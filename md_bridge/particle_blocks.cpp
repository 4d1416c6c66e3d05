#include "md_bridge/particle_blocks.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <functional>
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

namespace {

// Sends `send` (kPacked values per particle, grouped by destination rank: values[k] of them to
// rank k) and returns what every rank sent to this one, in rank order (collective).
std::vector<double> exchange(const std::vector<double>& send, const std::vector<int>& values,
                             MPI_Comm comm) {
  const std::size_t ranks = values.size();
  std::vector<int> send_offsets(ranks, 0), receive_counts(ranks), receive_offsets(ranks, 0);
  for (std::size_t k = 1; k < ranks; ++k) send_offsets[k] = send_offsets[k - 1] + values[k - 1];
  MPI_Alltoall(values.data(), 1, MPI_INT, receive_counts.data(), 1, MPI_INT, comm);
  long long received = 0;
  for (std::size_t k = 0; k < ranks; ++k) {
    receive_offsets[k] = int(received);
    received += receive_counts[k];
  }
  std::vector<double> receive(static_cast<std::size_t>(received));
  MPI_Alltoallv(send.data(), values.data(), send_offsets.data(), MPI_DOUBLE, receive.data(),
                receive_counts.data(), receive_offsets.data(), MPI_DOUBLE, comm);
  return receive;
}

// Particle i of (x, v) packed as id, x, y, v_x, v_y at p.
void pack(double* p, long long id, const double* x, const double* v, std::size_t i) {
  p[0] = double(id);
  p[1] = x[3 * i];
  p[2] = x[3 * i + 1];
  p[3] = v[3 * i];
  p[4] = v[3 * i + 1];
}

// The particles each go to the ranks `destinations(i)` lists (collective).
std::vector<double> send_to(std::size_t count, const long long* ids, const double* x,
                            const double* v, int ranks,
                            const std::function<void(std::size_t, std::vector<int>&)>& destinations,
                            MPI_Comm comm) {
  std::vector<std::vector<double>> to(static_cast<std::size_t>(ranks));
  std::vector<int> where;
  for (std::size_t i = 0; i < count; ++i) {
    where.clear();
    destinations(i, where);
    for (const int k : where) {
      auto& list = to[std::size_t(k)];
      list.resize(list.size() + kPacked);
      pack(&list[list.size() - kPacked], ids[i], x, v, i);
    }
  }
  std::vector<int> values(static_cast<std::size_t>(ranks));
  std::vector<double> send;
  for (int k = 0; k < ranks; ++k) {
    values[std::size_t(k)] =
        checked_count((long long)to[std::size_t(k)].size(), "one rank's particles");
    send.insert(send.end(), to[std::size_t(k)].begin(), to[std::size_t(k)].end());
    to[std::size_t(k)] = {};
  }
  return exchange(send, values, comm);
}

}  // namespace

ParticleFrame block_frame(const LocalParticles& local, const std::vector<long long>& ids,
                          long long n, MPI_Comm comm) {
  int ranks = 1, rank = 0;
  MPI_Comm_size(comm, &ranks);
  MPI_Comm_rank(comm, &rank);
  const std::size_t count = std::size_t(local.count);
  if (ids.size() != count)
    throw std::logic_error("particle frame: " + std::to_string(ids.size()) + " IDs for " +
                           std::to_string(count) + " local particles");
  // The largest block is the same on every rank, so all refuse it together.
  checked_count(kPacked * (n / ranks + 1), "one rank's block");
  bool ids_valid = true;
  const std::vector<double> receive = send_to(
      count, ids.data(), local.x, local.v, ranks,
      [&](std::size_t i, std::vector<int>& to) {
        const long long row = ids[i] - 1;
        if (row < 0 || row >= n) {
          ids_valid = false;
          return;
        }
        to.push_back(id_block_owner(row, n, ranks));
      },
      comm);

  const IdBlock block = id_block(n, ranks, rank);
  ParticleFrame frame;
  frame.x.assign(std::size_t(3 * block.count), 0.0);
  frame.v.assign(std::size_t(3 * block.count), 0.0);
  std::vector<char> seen(std::size_t(block.count), 0);
  const long long received = (long long)receive.size();
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

ParticleSample to_subdomains(const ParticleSample& mine, const double lo[2], const double hi[2],
                             double margin, MPI_Comm comm) {
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  const double own[4] = {lo[0] - margin, hi[0] + margin, lo[1] - margin, hi[1] + margin};
  std::vector<double> boxes(4 * std::size_t(ranks));
  MPI_Allgather(own, 4, MPI_DOUBLE, boxes.data(), 4, MPI_DOUBLE, comm);
  const std::vector<double> receive = send_to(
      std::size_t(mine.count()), mine.id.data(), mine.x.data(), mine.v.data(), ranks,
      [&](std::size_t i, std::vector<int>& to) {
        const double x = mine.x[3 * i], y = mine.x[3 * i + 1];
        for (int k = 0; k < ranks; ++k) {
          const double* b = &boxes[4 * std::size_t(k)];
          if (x >= b[0] && x < b[1] && y >= b[2] && y < b[3]) to.push_back(k);
        }
      },
      comm);
  ParticleSample sample;
  const std::size_t n = receive.size() / kPacked;
  sample.x.assign(3 * n, 0.0);
  sample.v.assign(3 * n, 0.0);
  sample.id.resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    const double* p = &receive[kPacked * j];
    sample.id[j] = std::llround(p[0]);
    sample.x[3 * j] = p[1];
    sample.x[3 * j + 1] = p[2];
    sample.v[3 * j] = p[3];
    sample.v[3 * j + 1] = p[4];
  }
  return sample;
}

}  // namespace granvv::md
