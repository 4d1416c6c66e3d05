// The initial-condition registry: the case schema's initial.* keys are derived from the
// generators' own declarations, and each generator gives its known fields and references.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "fields/constants.hpp"
#include "hydro/dilute_closure.hpp"
#include "hydro/initial_condition_registry.hpp"
#include "scene/case_schema.hpp"

namespace granvv::hydro {
namespace {

ParameterSet with_transverse(ParameterSet values, double b = 0.0, long long k = 1) {
  values.set("transverse_amplitude", b);
  values.set("transverse_mode", k);
  return values;
}

TEST(InitialConditionRegistry, SchemaKeysAreTheDeclaredParameters) {
  const app::KeySpec* type = app::find_key_spec("initial.type");
  ASSERT_NE(type, nullptr);
  std::vector<std::string> names;
  for (const auto& t : initial_condition_types()) names.push_back(t.name);
  EXPECT_EQ(type->constraint.choices, names);
  EXPECT_EQ(names, (std::vector<std::string>{"uniform", "single_mode", "random_modes",
                                             "linear_mode", "expression", "table", "snapshot"}));

  std::vector<std::string> schema_keys;
  for (const auto& spec : app::case_schema()) {
    if (spec.section() == "initial" && spec.leaf() != "type") schema_keys.push_back(spec.leaf());
  }
  std::vector<std::string> declared;
  for (const auto& key : initial_parameter_keys()) {
    declared.push_back(key.spec.name);
    const app::KeySpec* row = app::find_key_spec("initial." + key.spec.name);
    ASSERT_NE(row, nullptr) << key.spec.name;
    const app::ValueType expected = key.spec.is_integer()       ? app::ValueType::integer
                                    : key.spec.is_text()        ? app::ValueType::string
                                    : key.spec.is_named_reals() ? app::ValueType::real_table
                                                                : app::ValueType::real;
    EXPECT_EQ(row->type, expected) << key.spec.name;
    EXPECT_EQ(row->default_value.value.index(), static_cast<std::size_t>(expected));
    EXPECT_EQ(row->constraint.choices, key.spec.range.choices) << key.spec.name;
    EXPECT_EQ(row->constraint.min, key.spec.range.min) << key.spec.name;
    // An integer read as an int: without a declared bound the schema puts INT_MAX.
    const std::optional<double> max = key.spec.is_integer() && !key.spec.range.max
                                          ? std::optional<double>(2147483647.0)
                                          : key.spec.range.max;
    EXPECT_EQ(row->constraint.max, max) << key.spec.name;
  }
  EXPECT_EQ(schema_keys, declared);
}

TEST(InitialConditionRegistry, SharedParameterNamesEveryTypeThatReadsIt) {
  EXPECT_EQ(app::find_key_spec("initial.mode")->description,
            "single_mode/linear_mode: wave number k");
  EXPECT_EQ(app::find_key_spec("initial.seed")->description, "random_modes: random seed");
  EXPECT_EQ(app::find_key_spec("initial.transverse_mode")->description,
            "mode k_y of the transverse velocity");
}

TEST(InitialConditionRegistry, UnknownTypeAndMistypedParameterThrow) {
  EXPECT_THROW(find_initial_condition("sine"), std::invalid_argument);
  EXPECT_THROW(initial_parameters("sine", {}), std::invalid_argument);
  const ParameterSet p = {{"mode", 2LL}, {"velocity_amplitude", -0.05}};
  EXPECT_THROW(p.real("mode"), std::logic_error);
  EXPECT_THROW(p.integer("velocity_amplitude"), std::logic_error);
  EXPECT_THROW(p.real("seed"), std::logic_error);
}

// Paper Eq. (7): v = a sin(2 pi k x); at x = 1/(4k) the sine is 1 exactly in floating point.
TEST(InitialConditionRegistry, SingleModeFieldsAndItsExactInertiaReference) {
  const auto p = initial_parameters(
      "single_mode", with_transverse({{"velocity_amplitude", -0.05}, {"mode", 2LL}}));
  const InitialFields f = make_initial_fields(p, {});
  EXPECT_EQ(f.v(0.125), -0.05);
  EXPECT_EQ(f.dv(0.0), -0.05 * 2.0 * kPi * 2);
  EXPECT_EQ(f.n(0.3), 1.0);
  EXPECT_EQ(f.T(-0.2), 1.0);
  EXPECT_EQ(f.vy(0.1), 0.0);
  const auto inertia = inertia_reference(p);
  ASSERT_TRUE(inertia);
  EXPECT_DOUBLE_EQ(inertia->flow.singularity_time(), 1.0 / (2.0 * kPi * 0.05 * 2));  // Eq. (7)
  EXPECT_EQ(inertia->velocity_scale, 0.05);
  EXPECT_FALSE(seeded_eigenmode(p));

  // No velocity, no flow by inertia to compare with.
  EXPECT_FALSE(inertia_reference(initial_parameters(
      "single_mode", with_transverse({{"velocity_amplitude", 0.0}, {"mode", 1LL}}))));
  EXPECT_FALSE(inertia_reference(initial_parameters("uniform", with_transverse({}))));
}

TEST(InitialConditionRegistry, LinearModeSeedsItsEigenmodeAndMustBeSmall) {
  const ParameterSet values =
      with_transverse({{"mode", 3LL}, {"linear_branch", 1LL}, {"linear_amplitude", 1e-6}});
  const auto p = initial_parameters("linear_mode", values);
  const auto seeded = seeded_eigenmode(p);
  ASSERT_TRUE(seeded);
  EXPECT_EQ(seeded->mode, 3);
  EXPECT_EQ(seeded->branch, 1);
  EXPECT_FALSE(inertia_reference(p));
  EXPECT_FALSE(initial_parameter_problem(p, false));

  ParameterSet large = values;
  large.set("linear_amplitude", 0.02);
  const auto problem = initial_parameter_problem(initial_parameters("linear_mode", large), false);
  ASSERT_TRUE(problem);
  EXPECT_EQ(problem->parameter, "linear_amplitude");
  large.set("linear_amplitude", 0.01);  // the bound is allowed
  EXPECT_FALSE(initial_parameter_problem(initial_parameters("linear_mode", large), false));
}

// v_y = b cos(2 pi k_y x) on top of any type; it needs hydro.transverse_velocity.
TEST(InitialConditionRegistry, TransverseVelocityOnAnyType) {
  const auto p = initial_parameters("uniform", with_transverse({}, 0.2, 3));
  const InitialFields f = make_initial_fields(p, {});
  EXPECT_EQ(f.vy(0.0), 0.2);
  EXPECT_NEAR(f.vy(1.0 / 6.0), -0.2, 1e-15);  // cos(pi), to the rounding of 2 pi k x
  EXPECT_EQ(f.v(0.1), 0.0);
  const auto problem = initial_parameter_problem(p, false);
  ASSERT_TRUE(problem);
  EXPECT_EQ(problem->parameter, "transverse_amplitude");
  EXPECT_FALSE(initial_parameter_problem(p, true));
}

// Paper Figs. 1-2: the same seed gives the same scene; another seed another one.
TEST(InitialConditionRegistry, RandomModesAreReproducibleFromTheSeed) {
  const auto& random_modes = find_initial_condition("random_modes");
  const ParameterSet a = {{"random_modes", 5LL}, {"random_amplitude", 1e-2}, {"seed", 4LL}};
  ParameterSet b = a;
  b.set("seed", 5LL);
  const auto fa = random_modes.generate(a, DiluteClosure(Physics{})),
             fa2 = random_modes.generate(a, DiluteClosure(Physics{}));
  const auto fb = random_modes.generate(b, DiluteClosure(Physics{}));
  EXPECT_EQ(fa.n(0.17), fa2.n(0.17));
  EXPECT_NE(fa.n(0.17), fb.n(0.17));
  // Five modes of amplitude <= 1e-2 each.
  EXPECT_LE(std::abs(fa.n(0.17) - 1.0), 5e-2);
}

}  // namespace
}  // namespace granvv::hydro
