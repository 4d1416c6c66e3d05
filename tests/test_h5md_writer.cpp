// The H5MD particle writer (md_bridge/h5md_writer.hpp) on real files: the H5MD 1.1 layout
// and attributes, shapes, chunking and values of three frames of 100 particles, wrapping into
// the box, observables, a file read (from a copy) while the writer is still open, a file left
// by a killed process, argument errors, and block files joined by virtual datasets (the layout
// of a run on several MPI ranks) read as one file, also after the folder moved, and continued.
#include <H5Cpp.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "md_bridge/h5md_writer.hpp"
#include "md_bridge/particle_blocks.hpp"

namespace {

namespace fs = std::filesystem;
using granvv::md::H5mdWriter;

constexpr long long kN = 100;
constexpr double kLx = 40.0, kLy = 10.0;

// A fresh directory per test, removed afterwards.
class H5mdWriterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("granvv_h5md_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string file(const std::string& name) const { return (dir_ / name).string(); }

  fs::path dir_;
};

// Frame f of a deterministic particle set in LAMMPS layout: positions partly outside the box
// (up to two box lengths away), velocities, z filled with junk that must be ignored.
struct Frame {
  std::vector<double> x, v;
};
Frame make_frame(int f) {
  std::mt19937_64 rng(1234 + f);
  std::uniform_real_distribution<double> ux(-2.5 * kLx, 2.5 * kLx), uy(-2.5 * kLy, 2.5 * kLy),
      uv(-3.0, 3.0);
  Frame fr;
  for (long long i = 0; i < kN; ++i) {
    fr.x.insert(fr.x.end(), {ux(rng), uy(rng), 99.0});
    fr.v.insert(fr.v.end(), {uv(rng), uv(rng), -99.0});
  }
  // Exact edges: -L/2 stays, +L/2 maps to -L/2, and an inside point is untouched.
  fr.x[0] = -0.5 * kLx, fr.x[1] = 0.5 * kLy;
  fr.x[3] = 0.5 * kLx, fr.x[4] = -0.5 * kLy;
  fr.x[6] = 1.25, fr.x[7] = -3.5;
  return fr;
}
long long step_of(int f) {
  return 1000LL * f;
}
double time_of(int f) {
  return 0.125 * f;
}

std::vector<hsize_t> dims_of(const H5::DataSet& ds, std::vector<hsize_t>* max_dims = nullptr) {
  const auto space = ds.getSpace();
  std::vector<hsize_t> dims(space.getSimpleExtentNdims()), max(dims.size());
  space.getSimpleExtentDims(dims.data(), max.data());
  if (max_dims) *max_dims = max;
  return dims;
}

std::vector<double> read_doubles(const H5::DataSet& ds) {
  hsize_t total = 1;
  for (const auto d : dims_of(ds)) total *= d;
  std::vector<double> out(total);
  if (total) ds.read(out.data(), H5::PredType::NATIVE_DOUBLE);
  return out;
}

std::vector<std::int64_t> read_int64(const H5::DataSet& ds) {
  std::vector<std::int64_t> out(dims_of(ds).at(0));
  if (!out.empty()) ds.read(out.data(), H5::PredType::NATIVE_INT64);
  return out;
}

// A scalar, fixed-length string attribute (H5MD requires fixed length).
std::string string_attribute(const H5::H5Object& object, const std::string& name) {
  const auto attr = object.openAttribute(name);
  EXPECT_EQ(attr.getTypeClass(), H5T_STRING) << name;
  const auto type = attr.getStrType();
  EXPECT_FALSE(type.isVariableStr()) << name;
  EXPECT_EQ(attr.getSpace().getSimpleExtentType(), H5S_SCALAR) << name;
  std::string value;
  attr.read(type, value);
  return value.c_str();  // drop the padding
}

double wrapped_expected(double x, double length) {
  double y = std::fmod(x + 0.5 * length, length);
  if (y < 0) y += length;
  return y - 0.5 * length;
}

void write_frames(H5mdWriter& writer, int first, int last) {
  for (int f = first; f < last; ++f) {
    const auto fr = make_frame(f);
    writer.append_particles(step_of(f), time_of(f), fr.x, fr.v);
    for (const auto& name : H5mdWriter::standard_observables())
      writer.append_observable(name, step_of(f), time_of(f), 10.0 * f + name.size());
  }
}

// Checks the first `frames` frames of positions, velocities and observables.
void expect_frames(const H5::H5File& file, int frames, H5D_layout_t layout = H5D_CHUNKED) {
  for (const std::string element : {"position", "velocity"}) {
    SCOPED_TRACE(element);
    const auto group = file.openGroup("/particles/all/" + element);
    std::vector<hsize_t> max_dims;
    const auto value = group.openDataSet("value");
    ASSERT_EQ(dims_of(value, &max_dims), (std::vector<hsize_t>{hsize_t(frames), kN, 2}));
    EXPECT_EQ(max_dims, (std::vector<hsize_t>{H5S_UNLIMITED, kN, 2}));
    EXPECT_EQ(value.getCreatePlist().getLayout(), layout);
    EXPECT_EQ(value.getTypeClass(), H5T_FLOAT);
    const auto step_ds = group.openDataSet("step");
    EXPECT_EQ(step_ds.getTypeClass(), H5T_INTEGER);
    EXPECT_EQ(step_ds.getIntType().getSize(), 8u);
    const auto time_ds = group.openDataSet("time");
    EXPECT_EQ(time_ds.getTypeClass(), H5T_FLOAT);
    const auto steps = read_int64(step_ds);
    const auto times = read_doubles(time_ds);
    ASSERT_EQ(steps.size(), size_t(frames));
    ASSERT_EQ(times.size(), size_t(frames));
    const auto data = read_doubles(value);
    for (int f = 0; f < frames; ++f) {
      EXPECT_EQ(steps[f], step_of(f));
      EXPECT_EQ(times[f], time_of(f));
      const auto fr = make_frame(f);
      for (long long i = 0; i < kN; ++i) {
        const double* got = &data[(f * kN + i) * 2];
        if (element == "velocity") {
          EXPECT_EQ(got[0], fr.v[3 * i]);
          EXPECT_EQ(got[1], fr.v[3 * i + 1]);
          continue;
        }
        EXPECT_GE(got[0], -0.5 * kLx);
        EXPECT_LT(got[0], 0.5 * kLx);
        EXPECT_GE(got[1], -0.5 * kLy);
        EXPECT_LT(got[1], 0.5 * kLy);
        EXPECT_NEAR(got[0], wrapped_expected(fr.x[3 * i], kLx), 1e-12 * kLx) << f << " " << i;
        EXPECT_NEAR(got[1], wrapped_expected(fr.x[3 * i + 1], kLy), 1e-12 * kLy) << f << " " << i;
      }
      if (element == "velocity") continue;
      // The exact edges and the inside point of make_frame().
      EXPECT_EQ(data[f * kN * 2 + 0], -0.5 * kLx);
      EXPECT_EQ(data[f * kN * 2 + 1], -0.5 * kLy);
      EXPECT_EQ(data[f * kN * 2 + 2], -0.5 * kLx);
      EXPECT_EQ(data[f * kN * 2 + 3], -0.5 * kLy);
      EXPECT_EQ(data[f * kN * 2 + 4], 1.25);
      EXPECT_EQ(data[f * kN * 2 + 5], -3.5);
    }
  }
  for (const auto& name : H5mdWriter::standard_observables()) {
    SCOPED_TRACE(name);
    const auto group = file.openGroup("/observables/" + name);
    std::vector<hsize_t> max_dims;
    const auto value = group.openDataSet("value");
    ASSERT_EQ(dims_of(value, &max_dims), (std::vector<hsize_t>{hsize_t(frames)}));
    EXPECT_EQ(max_dims, (std::vector<hsize_t>{H5S_UNLIMITED}));
    const auto values = read_doubles(value);
    const auto steps = read_int64(group.openDataSet("step"));
    const auto times = read_doubles(group.openDataSet("time"));
    ASSERT_EQ(steps.size(), size_t(frames));
    ASSERT_EQ(times.size(), size_t(frames));
    for (int f = 0; f < frames; ++f) {
      EXPECT_EQ(values[f], 10.0 * f + name.size());
      EXPECT_EQ(steps[f], step_of(f));
      EXPECT_EQ(times[f], time_of(f));
    }
  }
}

TEST_F(H5mdWriterTest, WritesTheH5mdLayoutAndAttributes) {
  const auto path = file("run.h5");
  {
    H5mdWriter writer(path, kN, kLx, kLy, "0.1.0+test", "A. Author");
    write_frames(writer, 0, 3);
    EXPECT_EQ(writer.particle_frames(), 3);
    EXPECT_EQ(writer.observable_frames("total_energy"), 3);
  }
  H5::H5File file(path, H5F_ACC_RDONLY);

  const auto h5md = file.openGroup("/h5md");
  const auto version = h5md.openAttribute("version");
  EXPECT_EQ(version.getTypeClass(), H5T_INTEGER);
  std::vector<hsize_t> vdims(1);
  ASSERT_EQ(version.getSpace().getSimpleExtentNdims(), 1);
  version.getSpace().getSimpleExtentDims(vdims.data());
  ASSERT_EQ(vdims[0], 2u);
  int v[2] = {0, 0};
  version.read(H5::PredType::NATIVE_INT, v);
  EXPECT_EQ(v[0], 1);
  EXPECT_EQ(v[1], 1);
  EXPECT_EQ(string_attribute(file.openGroup("/h5md/author"), "name"), "A. Author");
  EXPECT_EQ(string_attribute(file.openGroup("/h5md/creator"), "name"), "granvv");
  EXPECT_EQ(string_attribute(file.openGroup("/h5md/creator"), "version"), "0.1.0+test");

  const auto box = file.openGroup("/particles/all/box");
  const auto dimension = box.openAttribute("dimension");
  EXPECT_EQ(dimension.getTypeClass(), H5T_INTEGER);
  EXPECT_EQ(dimension.getSpace().getSimpleExtentType(), H5S_SCALAR);
  int d = 0;
  dimension.read(H5::PredType::NATIVE_INT, &d);
  EXPECT_EQ(d, 2);
  const auto boundary = box.openAttribute("boundary");
  ASSERT_EQ(boundary.getTypeClass(), H5T_STRING);
  const auto btype = boundary.getStrType();
  EXPECT_FALSE(btype.isVariableStr());
  hsize_t bdims[1] = {0};
  ASSERT_EQ(boundary.getSpace().getSimpleExtentNdims(), 1);
  boundary.getSpace().getSimpleExtentDims(bdims);
  ASSERT_EQ(bdims[0], 2u);
  std::vector<char> bbuf(2 * btype.getSize());
  boundary.read(btype, bbuf.data());
  EXPECT_EQ(std::string(bbuf.data(), strnlen(bbuf.data(), btype.getSize())), "periodic");
  EXPECT_EQ(std::string(&bbuf[btype.getSize()], strnlen(&bbuf[btype.getSize()], btype.getSize())),
            "periodic");
  const auto edges = box.openDataSet("edges");
  EXPECT_EQ(dims_of(edges), std::vector<hsize_t>{2});
  EXPECT_EQ(read_doubles(edges), (std::vector<double>{kLx, kLy}));

  const auto ids = read_int64(file.openDataSet("/particles/all/id"));
  ASSERT_EQ(ids.size(), size_t(kN));
  for (long long i = 0; i < kN; ++i) EXPECT_EQ(ids[i], i + 1);

  // velocity shares position's step and time (hard links: two links to one object).
  H5O_info_t info;
  file.getObjinfo("/particles/all/position/step", info);
  EXPECT_EQ(info.rc, 2u);
  file.getObjinfo("/particles/all/velocity/time", info);
  EXPECT_EQ(info.rc, 2u);

  expect_frames(file, 3);
}

TEST_F(H5mdWriterTest, FileIsReadableWhileTheWriterIsOpen) {
  const auto path = file("live.h5"), copy = file("copy.h5");
  H5mdWriter writer(path, kN, kLx, kLy, "test");
  write_frames(writer, 0, 1);
  // The bytes on disk after one frame, as a reader (or a crash) would find them.
  fs::copy_file(path, copy, fs::copy_options::overwrite_existing);
  {
    H5::H5File file(copy, H5F_ACC_RDONLY);
    expect_frames(file, 1);
  }
  write_frames(writer, 1, 3);
  fs::copy_file(path, copy, fs::copy_options::overwrite_existing);
  H5::H5File file(copy, H5F_ACC_RDONLY);
  expect_frames(file, 3);
}

TEST_F(H5mdWriterTest, KilledWriterLeavesEveryAppendedFrame) {
  const auto path = file("killed.h5");
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    H5mdWriter writer(path, kN, kLx, kLy, "test");
    write_frames(writer, 0, 2);
    raise(SIGKILL);  // no destructor, no atexit: only what append() flushed survives
    _exit(3);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
  H5::H5File file(path, H5F_ACC_RDONLY);
  expect_frames(file, 2);
}

// A resumed run continues its file from the checkpoint's step: the frames written after it are
// dropped, the ones before kept bit for bit, and appending goes on from there.
TEST_F(H5mdWriterTest, ContinuedFileKeepsTheFramesUpToTheCheckpointAndAppendsAfterThem) {
  const auto path = file("resumed.h5");
  {
    H5mdWriter writer(path, kN, kLx, kLy, "test");
    write_frames(writer, 0, 5);  // frames 3 and 4 came after the checkpoint at frame 2
  }
  {
    H5mdWriter writer = H5mdWriter::continue_file(path, step_of(2), kN, kLx, kLy, "test");
    EXPECT_EQ(writer.particle_frames(), 3);
    EXPECT_EQ(writer.observable_frames("total_energy"), 3);
    write_frames(writer, 3, 5);
  }
  H5::H5File file(path, H5F_ACC_RDONLY);
  expect_frames(file, 5);
  EXPECT_FALSE(std::filesystem::exists(path + ".before-resume"));
  EXPECT_THROW(H5mdWriter::continue_file(this->file("absent.h5"), 0, kN, kLx, kLy, "test"),
               std::runtime_error);
}

// Three block files (the ID blocks of three ranks, particle_blocks.hpp) and their joined file,
// written as md_run writes them: each block its rows, then the joined file the frame's step.
struct BlockWriters {
  std::vector<granvv::md::H5mdBlock> blocks;
  std::vector<H5mdWriter> rows;
  H5mdWriter joined;
};
std::vector<granvv::md::H5mdBlock> three_blocks() {
  std::vector<granvv::md::H5mdBlock> blocks;
  for (int k = 0; k < 3; ++k) {
    const auto b = granvv::md::id_block(kN, 3, k);
    blocks.push_back({"run.rank000" + std::to_string(k) + ".h5", b.first, b.count});
  }
  return blocks;
}
void write_block_frames(BlockWriters& w, int first, int last) {
  for (int f = first; f < last; ++f) {
    const auto fr = make_frame(f);
    for (std::size_t k = 0; k < w.blocks.size(); ++k) {
      const auto& b = w.blocks[k];
      const std::vector<double> x(fr.x.begin() + 3 * b.first,
                                  fr.x.begin() + 3 * (b.first + b.count));
      const std::vector<double> v(fr.v.begin() + 3 * b.first,
                                  fr.v.begin() + 3 * (b.first + b.count));
      w.rows[k].append_particles(step_of(f), time_of(f), x, v);
    }
    w.joined.append_joined_frame(step_of(f), time_of(f));
    for (const auto& name : H5mdWriter::standard_observables())
      w.joined.append_observable(name, step_of(f), time_of(f), 10.0 * f + name.size());
  }
}

TEST(H5mdIdBlocks, CoverTheParticlesOnceInOrder) {
  for (const long long n : {1LL, 5LL, 100LL, 100001LL}) {
    for (const int ranks : {1, 2, 3, 7, 64}) {
      long long next = 0;
      for (int k = 0; k < ranks; ++k) {
        const auto b = granvv::md::id_block(n, ranks, k);
        EXPECT_EQ(b.first, next) << n << " " << ranks << " " << k;
        EXPECT_TRUE(b.count == n / ranks || b.count == n / ranks + 1);
        for (long long row = b.first; row < b.first + b.count; ++row)
          ASSERT_EQ(granvv::md::id_block_owner(row, n, ranks), k) << n << " " << ranks;
        next += b.count;
      }
      EXPECT_EQ(next, n);
    }
  }
}

TEST_F(H5mdWriterTest, BlockFilesJoinedByVirtualDatasetsReadAsOneFile) {
  const auto path = file("run.h5");
  {
    BlockWriters w{
        three_blocks(), {}, H5mdWriter::joined_file(path, kN, three_blocks(), kLx, kLy, "test")};
    for (const auto& b : w.blocks)
      w.rows.push_back(H5mdWriter::block_file(file(b.file), kN, b, kLx, kLy, "test"));
    write_block_frames(w, 0, 3);
    EXPECT_EQ(w.joined.particle_frames(), 3);
    EXPECT_EQ(w.rows[1].n_particles(), w.blocks[1].count);
    EXPECT_THROW(w.joined.append_particles(step_of(3), 1.0, make_frame(3).x, make_frame(3).v),
                 std::logic_error);
    EXPECT_THROW(w.rows[0].append_observable("total_energy", step_of(3), 1.0, 0.0),
                 std::logic_error);
  }
  {
    H5::H5File joined(path, H5F_ACC_RDONLY);
    expect_frames(joined, 3, H5D_VIRTUAL);
    const auto ids = read_int64(joined.openDataSet("/particles/all/id"));
    ASSERT_EQ(ids.size(), std::size_t(kN));
    for (long long i = 0; i < kN; ++i) EXPECT_EQ(ids[i], i + 1);
    // A block file holds only its rows: 33, 33 and 34 of the 100.
    H5::H5File block(file("run.rank0001.h5"), H5F_ACC_RDONLY);
    EXPECT_EQ(dims_of(block.openDataSet("/particles/all/position/value")),
              (std::vector<hsize_t>{3, 33, 2}));
    EXPECT_EQ(read_int64(block.openDataSet("/particles/all/id")).front(), 34);
    EXPECT_FALSE(block.nameExists("observables"));
  }
  EXPECT_EQ(H5mdWriter::joined_block_files(path),
            (std::vector<std::string>{"run.rank0000.h5", "run.rank0001.h5", "run.rank0002.h5"}));
  // The block files are found beside the joined file, wherever the folder goes.
  const fs::path moved = dir_.string() + "_moved";
  fs::remove_all(moved);
  fs::rename(dir_, moved);
  {
    H5::H5File joined((moved / "run.h5").string(), H5F_ACC_RDONLY);
    expect_frames(joined, 3, H5D_VIRTUAL);
  }
  fs::rename(moved, dir_);
  // A missing block file reads as NaN, not as zeros.
  fs::rename(file("run.rank0002.h5"), file("away.h5"));
  {
    H5::H5File joined(path, H5F_ACC_RDONLY);
    const auto x = read_doubles(joined.openDataSet("/particles/all/position/value"));
    EXPECT_TRUE(std::isnan(x.at(2 * (kN - 1))));
    EXPECT_FALSE(std::isnan(x.at(0)));
  }
  fs::rename(file("away.h5"), file("run.rank0002.h5"));
}

// A resumed multi-rank run: each block file and the joined file are cut back to the checkpoint.
TEST_F(H5mdWriterTest, ContinuedBlockAndJoinedFilesKeepTheFramesUpToTheCheckpoint) {
  const auto path = file("run.h5");
  const auto blocks = three_blocks();
  {
    BlockWriters w{blocks, {}, H5mdWriter::joined_file(path, kN, blocks, kLx, kLy, "test")};
    for (const auto& b : blocks)
      w.rows.push_back(H5mdWriter::block_file(file(b.file), kN, b, kLx, kLy, "test"));
    write_block_frames(w, 0, 5);
  }
  {
    BlockWriters w{
        blocks, {}, H5mdWriter::continue_joined_file(path, step_of(2), kN, blocks, kLx, kLy, "t")};
    for (const auto& b : blocks)
      w.rows.push_back(
          H5mdWriter::continue_block_file(file(b.file), step_of(2), kN, b, kLx, kLy, "t"));
    EXPECT_EQ(w.joined.particle_frames(), 3);
    EXPECT_EQ(w.rows[2].particle_frames(), 3);
    write_block_frames(w, 3, 5);
  }
  H5::H5File joined(path, H5F_ACC_RDONLY);
  expect_frames(joined, 5, H5D_VIRTUAL);
}

TEST_F(H5mdWriterTest, ExtraObservablesAreCreatedOnFirstUse) {
  const auto path = file("obs.h5");
  {
    H5mdWriter writer(path, 1, 1.0, 1.0, "test");
    writer.append_observable("collision_count", 5, 0.5, 7.0);
    writer.append_observable("collision_count", 6, 0.5, 9.0);  // equal times are allowed
    EXPECT_EQ(writer.observable_frames("collision_count"), 2);
    EXPECT_EQ(writer.observable_frames("total_energy"), 0);
    EXPECT_EQ(writer.observable_frames("no_such"), 0);
  }
  H5::H5File file(path, H5F_ACC_RDONLY);
  EXPECT_EQ(read_doubles(file.openDataSet("/observables/collision_count/value")),
            (std::vector<double>{7.0, 9.0}));
  EXPECT_EQ(read_int64(file.openDataSet("/observables/collision_count/step")),
            (std::vector<std::int64_t>{5, 6}));
  // The standard observables exist even without samples.
  EXPECT_EQ(dims_of(file.openDataSet("/observables/total_energy/value")), std::vector<hsize_t>{0});
  EXPECT_EQ(dims_of(file.openDataSet("/particles/all/position/value")),
            (std::vector<hsize_t>{0, 1, 2}));
}

TEST_F(H5mdWriterTest, RejectsBadArgumentsAndKeepsWhatWasWritten) {
  EXPECT_THROW(H5mdWriter(file("a.h5"), 0, kLx, kLy, "t"), std::invalid_argument);
  EXPECT_THROW(H5mdWriter(file("a.h5"), kN, -1.0, kLy, "t"), std::invalid_argument);
  EXPECT_THROW(H5mdWriter(file("a.h5"), kN, kLx, std::nan(""), "t"), std::invalid_argument);
  EXPECT_THROW(H5mdWriter(file("no_such_dir/a.h5"), kN, kLx, kLy, "t"), std::runtime_error);

  const auto path = file("b.h5");
  {
    H5mdWriter writer(path, kN, kLx, kLy, "t");
    write_frames(writer, 0, 2);
    const auto fr = make_frame(2);
    const std::vector<double> short_x(3 * kN - 3);
    EXPECT_THROW(writer.append_particles(5000, 1.0, short_x, fr.v), std::invalid_argument);
    EXPECT_THROW(writer.append_particles(step_of(1), 1.0, fr.x, fr.v), std::invalid_argument);
    EXPECT_THROW(writer.append_particles(5000, 0.0, fr.x, fr.v), std::invalid_argument);
    EXPECT_THROW(writer.append_particles(5000, std::nan(""), fr.x, fr.v), std::invalid_argument);
    EXPECT_THROW(writer.append_observable("total_energy", step_of(1), 1.0, 0.0),
                 std::invalid_argument);
    EXPECT_THROW(writer.append_observable("a/b", 1, 1.0, 0.0), std::invalid_argument);
    EXPECT_THROW(writer.append_observable("", 1, 1.0, 0.0), std::invalid_argument);
    EXPECT_EQ(writer.particle_frames(), 2);
    writer.close();
    writer.close();  // idempotent
    EXPECT_THROW(writer.append_particles(5000, 1.0, fr.x, fr.v), std::logic_error);
    EXPECT_THROW(writer.flush(), std::logic_error);
  }
  H5::H5File file(path, H5F_ACC_RDONLY);
  expect_frames(file, 2);
}

TEST(H5mdWrap, MapsIntoTheHalfOpenBox) {
  const double L = 7.3;
  EXPECT_EQ(H5mdWriter::wrap(0.0, L), 0.0);
  EXPECT_EQ(H5mdWriter::wrap(-0.5 * L, L), -0.5 * L);
  EXPECT_EQ(H5mdWriter::wrap(0.5 * L, L), -0.5 * L);
  EXPECT_NEAR(H5mdWriter::wrap(0.5 * L + 0.2, L), -0.5 * L + 0.2, 1e-12);
  EXPECT_NEAR(H5mdWriter::wrap(-0.5 * L - 0.2, L), 0.5 * L - 0.2, 1e-12);
  EXPECT_NEAR(H5mdWriter::wrap(3 * L + 1.0, L), 1.0, 1e-12);
  EXPECT_TRUE(std::isnan(H5mdWriter::wrap(std::nan(""), L)));
  // Points a rounding error away from an image of the edges stay in [-L/2, L/2).
  for (int k = -5; k <= 5; ++k) {
    for (const double edge : {-0.5 * L + k * L, 0.5 * L + k * L}) {
      for (const double x : {std::nextafter(edge, -1e300), edge, std::nextafter(edge, 1e300)}) {
        const double y = H5mdWriter::wrap(x, L);
        EXPECT_GE(y, -0.5 * L) << x;
        EXPECT_LT(y, 0.5 * L) << x;
      }
    }
  }
}

}  // namespace
