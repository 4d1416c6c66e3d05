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

// The particles each go to the ranks `destinations(i, list)` appends to list (collective),
// packed in one buffer by destination: counted first, then filled.
template <class Destinations>
std::vector<double> send_to(std::size_t count, const long long* ids, const double* x,
                            const double* v, int ranks, const Destinations& destinations,
                            MPI_Comm comm) {
  std::vector<int> values(static_cast<std::size_t>(ranks), 0), where;
  long long total = 0;
  for (std::size_t i = 0; i < count; ++i) {
    where.clear();
    destinations(i, where);
    for (const int k : where) values[std::size_t(k)] += kPacked;
    total += kPacked * (long long)where.size();
  }
  checked_count(total, "one rank's particles");
  std::vector<int> fill(static_cast<std::size_t>(ranks), 0);
  for (std::size_t k = 1; k < fill.size(); ++k) fill[k] = fill[k - 1] + values[k - 1];
  std::vector<double> send(static_cast<std::size_t>(total));
  for (std::size_t i = 0; i < count; ++i) {
    where.clear();
    destinations(i, where);
    for (const int k : where) {
      pack(&send[std::size_t(fill[std::size_t(k)])], ids[i], x, v, i);
      fill[std::size_t(k)] += kPacked;
    }
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
  const IdBlock block = id_block(n, ranks, rank);
  ParticleFrame frame;
  frame.x.assign(std::size_t(3 * block.count), 0.0);
  frame.v.assign(std::size_t(3 * block.count), 0.0);
  std::vector<char> seen(std::size_t(block.count), 0);
  long long placed = 0;
  bool complete = true;
  // Particle `id` into its row of this rank's block; false if it has no row or had one already.
  auto place = [&](long long id, double x, double y, double vx, double vy) {
    const long long row = id - 1 - block.first;
    if (row < 0 || row >= block.count || seen[std::size_t(row)]) return false;
    seen[std::size_t(row)] = 1;
    frame.x[std::size_t(3 * row)] = x;
    frame.x[std::size_t(3 * row + 1)] = y;
    frame.v[std::size_t(3 * row)] = vx;
    frame.v[std::size_t(3 * row + 1)] = vy;
    ++placed;
    return true;
  };
  if (ranks == 1) {  // every particle is this rank's: placed directly
    for (std::size_t i = 0; complete && i < count; ++i)
      complete =
          place(ids[i], local.x[3 * i], local.x[3 * i + 1], local.v[3 * i], local.v[3 * i + 1]);
  } else {
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
    complete = ids_valid;
    for (std::size_t j = 0; complete && j < receive.size(); j += kPacked) {
      const double* p = &receive[j];
      complete = place(static_cast<long long>(p[0]), p[1], p[2], p[3], p[4]);
    }
  }
  complete = complete && placed == block.count;
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
    sample.id[j] = static_cast<long long>(p[0]);
    sample.x[3 * j] = p[1];
    sample.x[3 * j + 1] = p[2];
    sample.v[3 * j] = p[3];
    sample.v[3 * j + 1] = p[4];
  }
  return sample;
}

}  // namespace granvv::md
