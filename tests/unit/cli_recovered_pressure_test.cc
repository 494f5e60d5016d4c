// The recovered contact pressure -n . sigma(u_h) . n in the contact CSV:
// on the contact patch tests the stress is uniform and exactly in every
// discretisation's space, so the recovered pressure must equal the
// applied pressure at every pair, as the pair pressure does (the
// reference is the scene's load, not this code's output).
#include <gtest/gtest.h>

#include "cli_helpers.h"
#include <string>
#include <vector>



TEST(CliRecoveredPressure, EqualsTheUniformPressureOfThePatchTests)
{
  const std::string prm = cli::join(std::string(IGABDE_SOURCE_DIR), "prm");
  struct Case
  {
    std::string scene, settings;
  };
  // Both scenes press with a uniform pressure 1 (their Tractions).
  const std::vector<Case> cases = {
    {"v3-contact-patch-2d.prm", "--set Discretization/Type=nurbs"},
    {"v3-contact-patch-2d.prm", "--set Discretization/Type=lagrange"},
    {"v3-contact-patch-2d.prm",
     "--set 'Contact/Friction coefficient=0.3' --set Contact/Path=full"},
    {"v3-contact-patch-3d.prm", "--set Discretization/Type=nurbs"},
    {"v3-contact-patch-3d.prm", "--set Discretization/Type=lagrange"}};
  for (unsigned int c = 0; c < cases.size(); ++c)
    {
      SCOPED_TRACE(cases[c].scene + " " + cases[c].settings);
      const cli::ScratchFolder folder("recovered-pressure-" +
                                      std::to_string(c));
      const auto               r =
        cli::run_igabde("'" + cli::join(prm, cases[c].scene) + "' " +
                          cases[c].settings +
                          " --quiet --set 'Output/Write vtu=false' --set "
                          "Output/Directory=out",
                        folder);
      ASSERT_EQ(r.status, 0) << r.output;
      const std::string   csv = cli::join(folder.path, "out/contact-0001.csv");
      const cli::CsvTable table = cli::read_table(csv);
      ASSERT_FALSE(table.rows.empty());
      for (unsigned int i = 0; i < table.rows.size(); ++i)
        {
          EXPECT_NEAR(table.number(i, "recovered_pressure"), 1., 1e-8)
            << "pair " << i;
          EXPECT_NEAR(table.number(i, "pressure"), 1., 1e-8) << "pair " << i;
        }
    }
}
