// FieldSeries (fields/field_series.hpp): its one HDF5 layout read back exactly, refusals of
// malformed series, the ensemble over members against hand-computed means and errors, and the
// hydro's cell fields against a state whose fields are known.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "compare/ensemble_fields.hpp"
#include "compare/side_by_side.hpp"
#include "fields/field_series.hpp"
#include "fields/field_series_file.hpp"
#include "hydro/cell_fields.hpp"

namespace {

using granvv::fields::FieldSeries;
using granvv::fields::FieldSnapshot;
using granvv::fields::Geometry;
namespace fs = std::filesystem;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

fs::path scratch_file(const std::string& name) {
  return fs::temp_directory_path() / ("granvv-" + name + "-" + std::to_string(::getpid()) + ".h5");
}

// Element-wise equality that counts NaN == NaN (bins without a value stay NaN in the file).
void expect_same(const std::vector<double>& a, const std::vector<double>& b, const char* what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::isnan(a[i])) {
      EXPECT_TRUE(std::isnan(b[i])) << what << "[" << i << "]";
    } else {
      EXPECT_EQ(a[i], b[i]) << what << "[" << i << "]";
    }
  }
}

FieldSeries round_trip(const FieldSeries& s, const std::string& name) {
  const fs::path file = scratch_file(name);
  {
    H5::H5File h5(file.string(), H5F_ACC_TRUNC);
    H5::Group g = h5.createGroup("/fields");
    granvv::fields::write_field_series(g, s);
  }
  H5::H5File h5(file.string(), H5F_ACC_RDONLY);
  FieldSeries back = granvv::fields::read_field_series(h5.openGroup("/fields"));
  fs::remove(file);
  return back;
}

void expect_same_series(const FieldSeries& a, const FieldSeries& b) {
  EXPECT_EQ(a.geometry, b.geometry);
  expect_same(a.bin_edges, b.bin_edges, "bin_edges");
  ASSERT_EQ(a.snapshots.size(), b.snapshots.size());
  for (std::size_t k = 0; k < a.snapshots.size(); ++k) {
    EXPECT_EQ(a.snapshots[k].t, b.snapshots[k].t);
    EXPECT_EQ(a.snapshots[k].label, b.snapshots[k].label);
    for (const auto& c : granvv::fields::field_columns()) {
      expect_same(a.snapshots[k].*c.values, b.snapshots[k].*c.values, c.name);
      if (c.standard_error) {
        expect_same(a.snapshots[k].*c.standard_error, b.snapshots[k].*c.standard_error, c.name);
      }
    }
  }
}

TEST(FieldSeries, CellsWithMovingPositionsAndNoErrorsReadBackExactly) {
  FieldSeries s;  // two snapshots of a 3-cell Lagrangian mesh, transverse flow carried
  s.snapshots.push_back({0.0,
                         "initial",
                         {-0.4, 0.0, 0.3},
                         {1, 2, 3},
                         {0.1, 0.2, 0.3},
                         {0.0, -0.1, 0.1},
                         {1, 1, 1},
                         {},
                         {},
                         {},
                         {},
                         {},
                         {},
                         {},
                         {},
                         {},
                         {},
                         {},
                         {},
                         {},
                         {},
                         {},
                         {}});
  s.snapshots.push_back({0.5,
                         "final",
                         {-0.41, 0.02, 0.33},
                         {1.5, 2, 2.5},
                         {0.1, 0.1, 0.3},
                         {0.0, -0.2, 0.1},
                         {0.9, 0.8, 0.7},
                         {},
                         {},
                         {},
                         {},
                         {},
                         {},
                         {},
                         {},
                         {},
                         {},
                         {},
                         {},
                         {},
                         {},
                         {},
                         {}});
  expect_same_series(s, round_trip(s, "cells"));
}

TEST(FieldSeries, BinsWithErrorsCountsAndNaNReadBackExactly) {
  FieldSeries s = FieldSeries::on_bins(-2.0, 4.0, 2);
  s.snapshots.push_back({0.0,
                         "output",
                         {-1, 1},
                         {0.5, 0.7},
                         {0.1, kNaN},
                         {0.2, kNaN},
                         {1, kNaN},
                         {0.01, 0.02},
                         {0.03, kNaN},
                         {0.04, kNaN},
                         {0.05, kNaN},
                         {3, 0},
                         {0.5, 0.1},
                         {},
                         {},
                         {},
                         {},
                         {},
                         {},
                         {},
                         {},
                         {},
                         {}});
  const FieldSeries back = round_trip(s, "bins");
  expect_same_series(s, back);
  expect_same(back.bin_edges, {-2.0, 0.0, 2.0}, "edges of on_bins");
}

TEST(FieldSeries, EmptySeriesKeepsItsGeometry) {
  const FieldSeries s = FieldSeries::on_bins(0.0, 1.0, 4);
  const FieldSeries back = round_trip(s, "empty");
  EXPECT_EQ(back.geometry, Geometry::bins);
  EXPECT_TRUE(back.snapshots.empty());
  EXPECT_EQ(back.bin_edges.size(), 5u);
}

TEST(FieldSeries, SnapshotsThatDisagreeInLengthAreRefused) {
  FieldSeries s;
  s.snapshots.push_back({0.0, "initial", {0, 0.5}, {1, 1}, {0, 0}, {}, {1, 1}, {}, {}, {}, {}, {},
                         {},  {},        {},       {},     {},     {}, {},     {}, {}, {}, {}});
  s.snapshots.push_back({1.0, "final", {0, 0.5}, {1, 1, 1}, {0, 0}, {}, {1, 1}, {}, {}, {}, {}, {},
                         {},  {},      {},       {},        {},     {}, {},     {}, {}, {}, {}});
  const fs::path file = scratch_file("ragged");
  H5::H5File h5(file.string(), H5F_ACC_TRUNC);
  H5::Group g = h5.createGroup("/fields");
  EXPECT_THROW(granvv::fields::write_field_series(g, s), std::invalid_argument);
  fs::remove(file);
}

TEST(FieldSeries, AGroupWithoutTheLayoutIsRefused) {
  const fs::path file = scratch_file("not-a-series");
  H5::H5File h5(file.string(), H5F_ACC_TRUNC);
  H5::Group g = h5.createGroup("/other");
  H5::Exception::dontPrint();
  EXPECT_ANY_THROW(granvv::fields::read_field_series(g));
  fs::remove(file);
  EXPECT_THROW(granvv::fields::field_column("rho"), std::invalid_argument);
}

TEST(FieldSeries, HydrodynamicFieldsAreTheColumnsEveryComparisonWeighs) {
  const std::vector<std::string> expected = {"n", "v_x", "v_y", "T"};
  EXPECT_EQ(granvv::fields::hydrodynamic_fields(), expected);
  EXPECT_EQ(granvv::compare::fields_with_errors(), expected);
  for (const auto& name : expected) {
    EXPECT_NE(granvv::fields::field_column(name).standard_error, nullptr) << name;
  }
  EXPECT_EQ(granvv::compare::compared_fields(true), expected);
  EXPECT_EQ(granvv::compare::compared_fields(false), (std::vector<std::string>{"n", "v_x", "T"}));
}

TEST(FieldSeries, SameTimeIsEqualUpToTheRoundingOfAUnitConversion) {
  using granvv::fields::same_time;
  // A time in sigma sqrt(m/T0) converted to Lx / sqrt(T0/m) and back: a few ulp apart.
  const double lx = 396.07, t = 45.0 / lx;
  EXPECT_TRUE(same_time(t * lx / lx, t));
  EXPECT_TRUE(same_time(1.0 + 5e-10, 1.0));  // 1e-9 relative to max(1, t)
  EXPECT_FALSE(same_time(1.0 + 2e-9, 1.0));
  EXPECT_TRUE(same_time(5e-10, 0.0));  // absolute below t = 1
  EXPECT_FALSE(same_time(2e-9, 0.0));
  EXPECT_TRUE(same_time(1000.0 * (1.0 + 5e-10), 1000.0));
  EXPECT_FALSE(same_time(1000.0 * (1.0 + 2e-9), 1000.0));
}

TEST(EnsembleFieldSeries, MeanAndStandardErrorOfTwoMembersByHand) {
  // Two members: mean (a + b)/2, sample sd |a - b|/sqrt(2), error of the mean |a - b|/2.
  // A bin empty in one member (NaN) takes the other alone: its error is NaN (one value).
  FieldSeries a = FieldSeries::on_bins(0.0, 1.0, 2), b = a;
  a.snapshots.push_back({0.0, "output", {0.25, 0.75}, {1, 3},   {0.2, kNaN}, {0, 0}, {1, 2}, {},
                         {},  {},       {},           {10, 30}, {},          {},     {},     {},
                         {},  {},       {},           {},       {},          {},     {}});
  b.snapshots.push_back({0.0, "output", {0.25, 0.75}, {3, 3},   {0.4, 0.5}, {0, 0}, {3, 2}, {},
                         {},  {},       {},           {30, 30}, {},         {},     {},     {},
                         {},  {},       {},           {},       {},         {},     {}});
  const FieldSeries e = granvv::compare::ensemble_field_series({a, b});
  ASSERT_EQ(e.snapshots.size(), 1u);
  const FieldSnapshot& s = e.snapshots[0];
  expect_same(s.x, {0.25, 0.75}, "x");
  expect_same(s.n, {2, 3}, "n");
  expect_same(s.n_stderr, {1, 0}, "n_stderr");
  EXPECT_NEAR(s.v_x[0], 0.3, 1e-15);
  EXPECT_NEAR(s.v_x_stderr[0], 0.1, 1e-15);
  EXPECT_EQ(s.v_x[1], 0.5);
  EXPECT_TRUE(std::isnan(s.v_x_stderr[1]));
  expect_same(s.T, {2, 2}, "T");
  expect_same(s.count, {20, 30}, "count");
  expect_same(s.count_stderr, {10, 0}, "count_stderr");
  EXPECT_THROW(granvv::compare::ensemble_field_series({}), std::invalid_argument);
}

TEST(CellFieldSeries, DensityIsMassOverWidthAndVelocityTheNodeMean) {
  // Three cells of widths 0.2, 0.3, 0.5 with masses 0.2, 0.6, 0.2: n = 1, 2, 0.4 at the
  // centres -0.4, -0.15, 0.25; v the mean of the two nodes (periodic: the last cell's right
  // node is node 0).
  granvv::hydro::LagrangianState s;
  s.t = 0.7;
  s.node_x = {-0.5, -0.3, 0.0};
  s.node_v = {1.0, 3.0, -1.0};
  s.node_xi = s.node_x;
  s.cell_mass = {0.2, 0.6, 0.2};
  s.cell_T = {1.0, 0.5, 2.0};
  const FieldSeries f = granvv::hydro::cell_field_series({{"output", s}});
  EXPECT_EQ(f.geometry, Geometry::cells);
  ASSERT_EQ(f.snapshots.size(), 1u);
  const FieldSnapshot& c = f.snapshots[0];
  EXPECT_EQ(c.t, 0.7);
  EXPECT_EQ(c.label, "output");
  const double x[] = {-0.4, -0.15, 0.25}, n[] = {1.0, 2.0, 0.4}, v[] = {2.0, 1.0, 0.0};
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(c.x[i], x[i], 1e-15);
    EXPECT_NEAR(c.n[i], n[i], 1e-14);
    EXPECT_EQ(c.v_x[i], v[i]);
    EXPECT_EQ(c.T[i], s.cell_T[i]);
  }
  EXPECT_TRUE(c.v_y.empty()) << "no transverse velocity carried";
  EXPECT_TRUE(c.n_stderr.empty() && c.count.empty()) << "the hydro has no errors or counts";
}

}  // namespace
