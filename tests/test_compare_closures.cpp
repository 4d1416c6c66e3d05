// compare.closures through the real CLI: bad lists are refused with one line naming the key
// (exit 2, nothing written), and a shortened quickstart runs the particles once against two
// hydro closures, each compared on its own, with the usual compare block filled by the first.
#include <H5Cpp.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "fields/hdf5_datasets.hpp"
#include "support/cli_runner.hpp"

namespace granvv::testing {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct BadList {
  const char* list;    // the TOML value of compare.closures
  const char* reason;  // a part of the error line
};

TEST(CompareClosures, BadListsExitTwoWithOneLineNamingTheKey) {
  const BadList bad[] = {
      {"[\"nope\"]", "one of dilute, enskog"},
      {"[\"dilute\", \"dilute\"]", "repeats an earlier one"},
      {"[]", "at least one"},
      {"[\"enskog\", \"dilute\"]", "must be hydro.closure = \"dilute\""},
      {"[1, 2]", "an array of strings"},
  };
  for (const auto& b : bad) {
    SCOPED_TRACE(b.list);
    const fs::path dir = fresh_directory("closures-bad");
    const CliStreams r = run_cli_streams("run quickstart --set " +
                                         shell_quote(std::string("compare.closures=") + b.list) +
                                         " --out " + shell_quote((dir / "out").string()));
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line: " << r.err;
    EXPECT_NE(r.err.find("compare.closures"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(b.reason), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "out"));
    fs::remove_all(dir);
  }
}

// The default is [hydro.closure]: the resolved case lists it, and runs again as it is.
TEST(CompareClosures, DefaultIsTheHydroClosure) {
  const CliStreams r = run_cli_streams("run quickstart --dry-run --set hydro.closure=enskog");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("closures = [\"enskog\"]"), std::string::npos) << r.out;
}

// quickstart to t_MD = 50 with two seeds: the particles run once (one ensemble in /md), each
// closure gets its own window, verdict, hydro block with validity monitors, and results.h5
// groups; the top-level compare block is the first closure's entry, key for key.
TEST(CompareClosures, ShortQuickstartComparesEachClosureWithTheSameParticles) {
  const fs::path dir = fresh_directory("closures-run");
  const fs::path out = dir / "out";
  const CliStreams r = run_cli_streams(
      "run quickstart --quiet --no-report --set md.t_end=50 "
      "--set 'md.output_times=[0.0, 25.0, 50.0]' --set md.ensemble=2 "
      "--set 'compare.closures=[\"dilute\", \"enskog\"]' --out " +
      shell_quote(out.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json s = json::parse(read_text(out / "summary.json"));
  const json& c = s["compare"];
  ASSERT_TRUE(c["closures"].is_object()) << c.dump(2);
  EXPECT_EQ(c["closure_order"], json::array({"dilute", "enskog"}));
  for (const char* name : {"dilute", "enskog"}) {
    SCOPED_TRACE(name);
    const json& e = c["closures"][name];
    for (const char* key :
         {"agreement_window", "agreement_throughout", "first_field_to_leave", "left_at", "verdict",
          "disagreement", "fields", "peak", "haff", "monitors_fired_at_parting"}) {
      EXPECT_TRUE(e.contains(key)) << key;
    }
    EXPECT_EQ(e["hydro"]["closure"], name);
    EXPECT_TRUE(e["hydro"]["validity"]["area_fraction"]["applies"].get<bool>())
        << "a comparison knows phi0 = md.area_fraction";
    EXPECT_EQ(e["times"], c["times"]) << "the same particle snapshots";
    EXPECT_EQ(e["peak"]["md_n"], c["peak"]["md_n"]) << "the same particles";
  }
  // The first closure fills the usual blocks, unchanged.
  json first = c["closures"]["dilute"];
  first.erase("hydro");
  json top = c;
  top.erase("closures");
  top.erase("closure_order");
  EXPECT_EQ(first, top);
  EXPECT_EQ(s["hydro"]["closure"], "dilute");
  // Two different hydros from the same particle fields.
  const auto& dilute_peak = c["closures"]["dilute"]["peak"]["hydro_n"];
  const auto& enskog_peak = c["closures"]["enskog"]["peak"]["hydro_n"];
  ASSERT_EQ(dilute_peak.size(), enskog_peak.size());
  EXPECT_NE(dilute_peak.back(), enskog_peak.back());

  H5::Exception::dontPrint();
  H5::H5File h5((out / "results.h5").string(), H5F_ACC_RDONLY);
  for (const char* group :
       {"/compare/closures/dilute/fields/n", "/compare/closures/enskog/fields/n",
        "/hydro_closures/enskog/timeseries", "/hydro/timeseries"}) {
    EXPECT_TRUE(h5.nameExists(group)) << group;
  }
  EXPECT_FALSE(h5.nameExists("/hydro_closures/dilute")) << "the first closure's hydro is /hydro";
  EXPECT_TRUE(h5.nameExists("/hydro_closures/enskog/timeseries/phi_max"));

  // The particles' pressure against every closure's equation of state, at the particles' own
  // bins: the first closure's is /compare/pressure/eos, and Enskog's over dilute's is
  // F_p = 1 + (1 + r) phi chi(phi) with Henderson's chi at phi = phi0 n (docs/physics.md §9),
  // to round-off.
  const auto dilute_eos =
      h5::read_doubles(h5.openGroup("/compare/pressure/closures/dilute"), "eos");
  const auto enskog_eos =
      h5::read_doubles(h5.openGroup("/compare/pressure/closures/enskog"), "eos");
  EXPECT_EQ(dilute_eos.values, h5::read_doubles(h5.openGroup("/compare/pressure"), "eos").values);
  const auto n_md = h5::read_doubles(h5.openGroup("/compare/fields/n"), "md");
  ASSERT_EQ(n_md.values.size(), enskog_eos.values.size());
  const double phi0 = s["md"]["area_fraction"].get<double>();
  const double restitution = s["md"]["restitution"].get<double>();
  for (std::size_t i = 0; i < n_md.values.size(); ++i) {
    const double phi = phi0 * n_md.values[i];
    const double chi = (1 - 7 * phi / 16) / ((1 - phi) * (1 - phi));
    EXPECT_NEAR(enskog_eos.values[i] / dilute_eos.values[i], 1 + (1 + restitution) * phi * chi,
                1e-12)
        << i;
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace granvv::testing
