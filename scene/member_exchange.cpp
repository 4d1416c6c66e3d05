#include "scene/member_exchange.hpp"

#include <cstring>
#include <stdexcept>
#include <string>

namespace granvv::app {

namespace {

class Writer {
 public:
  void put(double value) { raw(&value, sizeof value); }
  void put(long long value) { raw(&value, sizeof value); }
  void put(const std::string& text) {
    put(static_cast<long long>(text.size()));
    raw(text.data(), text.size());
  }
  void put(const std::vector<double>& values) {
    put(static_cast<long long>(values.size()));
    raw(values.data(), values.size() * sizeof(double));
  }
  std::vector<char> bytes;

 private:
  void raw(const void* data, std::size_t size) {
    const char* begin = static_cast<const char*>(data);
    bytes.insert(bytes.end(), begin, begin + size);
  }
};

class Reader {
 public:
  explicit Reader(const std::vector<char>& bytes) : bytes_(bytes) {}
  double real() {
    double value = 0.0;
    raw(&value, sizeof value);
    return value;
  }
  long long integer() {
    long long value = 0;
    raw(&value, sizeof value);
    return value;
  }
  std::string text() {
    std::string value(length(1), '\0');
    raw(value.data(), value.size());
    return value;
  }
  std::vector<double> reals() {
    std::vector<double> values(length(sizeof(double)));
    raw(values.data(), values.size() * sizeof(double));
    return values;
  }

 private:
  std::size_t length(std::size_t element) {
    const long long n = integer();
    if (n < 0 || std::size_t(n) > (bytes_.size() - at_) / element)
      throw std::runtime_error("a member record that ends early");
    return std::size_t(n);
  }
  void raw(void* data, std::size_t size) {
    if (bytes_.size() - at_ < size) throw std::runtime_error("a member record that ends early");
    if (size > 0) std::memcpy(data, bytes_.data() + at_, size);
    at_ += size;
  }
  const std::vector<char>& bytes_;
  std::size_t at_ = 0;
};

}  // namespace

std::vector<char> encode_member_record(const MemberRecord& record) {
  Writer w;
  const md::MdRunResult& r = record.run;
  w.put(r.status);
  w.put(r.stop_reason);
  w.put(r.wall_seconds);
  w.put(r.steps);
  for (const auto& column : md::md_series_columns()) w.put(r.series.*column.values);
  w.put(static_cast<long long>(r.series.engine.size()));
  for (const auto& [name, values] : r.series.engine) {
    w.put(name);
    w.put(values);
  }
  w.put(fields::to_string(r.fields.geometry));
  w.put(r.fields.bin_edges);
  w.put(static_cast<long long>(r.fields.snapshots.size()));
  for (const auto& snapshot : r.fields.snapshots) {
    w.put(snapshot.t);
    w.put(snapshot.label);
    for (const auto& column : fields::field_columns()) {
      w.put(snapshot.*column.values);
      if (column.standard_error) w.put(snapshot.*column.standard_error);
    }
  }
  w.put(static_cast<long long>(record.totals.numbers.size()));
  for (const auto& [name, value] : record.totals.numbers) {
    w.put(name);
    w.put(value);
  }
  return w.bytes;
}

MemberRecord decode_member_record(const std::vector<char>& bytes) {
  Reader in(bytes);
  MemberRecord record;
  md::MdRunResult& r = record.run;
  r.status = in.text();
  r.stop_reason = in.text();
  r.wall_seconds = in.real();
  r.steps = in.integer();
  for (const auto& column : md::md_series_columns()) r.series.*column.values = in.reals();
  for (long long i = 0, n = in.integer(); i < n; ++i) {
    std::string name = in.text();
    r.series.engine.push_back({std::move(name), in.reals()});
  }
  r.fields.geometry = fields::geometry_from_string(in.text());
  r.fields.bin_edges = in.reals();
  for (long long i = 0, n = in.integer(); i < n; ++i) {
    fields::FieldSnapshot snapshot;
    snapshot.t = in.real();
    snapshot.label = in.text();
    for (const auto& column : fields::field_columns()) {
      snapshot.*column.values = in.reals();
      if (column.standard_error) snapshot.*column.standard_error = in.reals();
    }
    r.fields.snapshots.push_back(std::move(snapshot));
  }
  for (long long i = 0, n = in.integer(); i < n; ++i) {
    std::string name = in.text();
    record.totals.numbers.push_back({std::move(name), in.real()});
  }
  return record;
}

void share_member_records(std::vector<MemberRecord>& records, const std::function<int(int)>& owner,
                          MPI_Comm comm) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  if (ranks == 1) return;
  for (std::size_t m = 0; m < records.size(); ++m) {
    const int from = owner(int(m));
    std::vector<char> bytes;
    if (rank == from) bytes = encode_member_record(records[m]);
    long long size = static_cast<long long>(bytes.size());
    MPI_Bcast(&size, 1, MPI_LONG_LONG, from, comm);
    bytes.resize(std::size_t(size));
    MPI_Bcast(bytes.data(), int(size), MPI_CHAR, from, comm);
    if (rank != from) records[m] = decode_member_record(bytes);
  }
}

}  // namespace granvv::app
