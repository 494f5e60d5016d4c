// The name tables of the scene's choices (base/choice_names.h): each name
// is read back as the value it names (no two rows share a name or a
// value), the Selection text lists them in the table's order, and a text
// outside the table is refused.

#include <igabde/base/choice_names.h>

#include <igabde/discretization/settings.h>

#include <igabde/elasticity/material.h>

#include <igabde/contact/condensation.h>
#include <igabde/contact/contact_solver.h>
#include <igabde/contact/pairing.h>
#include <igabde/contact/path_cost.h>

#include <igabde/coupled/solver.h>
#include <igabde/scene/parameters.h>

#include <gtest/gtest.h>

#include <set>
#include <stdexcept>
#include <string>

using namespace igabde;

namespace
{
  template <typename Enum, std::size_t n>
  void
  expect_one_name_per_value(const base::ChoiceNames<Enum, n> &names)
  {
    std::set<std::string> seen_names;
    std::set<Enum>        seen_values;
    for (const auto &[value, name] : names)
      {
        EXPECT_TRUE(seen_names.insert(name).second) << "name " << name;
        EXPECT_TRUE(seen_values.insert(value).second) << "value of " << name;
        EXPECT_EQ(base::value_of(names, name), value) << name;
        EXPECT_EQ(base::name_of(names, value), name);
      }
    EXPECT_THROW(base::value_of(names, "no such choice"),
                 std::invalid_argument);
  }
} // namespace



TEST(ChoiceNames, EachTableNamesEachValueOnce)
{
  expect_one_name_per_value(contact::algorithm_names);
  expect_one_name_per_value(contact::path_names);
  expect_one_name_per_value(contact::pairing_names);
  expect_one_name_per_value(contact::condensation_names);
  expect_one_name_per_value(coupled::solver_names);
  expect_one_name_per_value(discretization::type_names);
  expect_one_name_per_value(discretization::linear_solver_names);
  expect_one_name_per_value(discretization::pair_placement_names);
  expect_one_name_per_value(elasticity::plane_model_names);
  expect_one_name_per_value(scene::body_type_names);
  expect_one_name_per_value(scene::geometry_names);
  expect_one_name_per_value(scene::exact_solution_type_names);
}



TEST(ChoiceNames, SelectionListsTheNamesInOrder)
{
  EXPECT_EQ(base::selection_of(contact::path_names), "condensed|full|auto");
  EXPECT_EQ(base::selection_of(scene::body_type_names),
            "deformable|rigid plane|rigid cylinder|rigid sphere|"
            "rigid surface|none");
  EXPECT_EQ(to_string(contact::Algorithm::augmented_lagrange),
            "augmented-lagrange");
  EXPECT_EQ(to_string(contact::Path::automatic), "auto");
}
