// The recovered contact pressure -n . sigma(u_h) . n in the contact CSV:
// on the contact patch tests the stress is uniform and exactly in every
// discretisation's space, so the recovered pressure must equal the
// applied pressure at every pair, as the pair pressure does (the
// reference is the scene's load, not this code's output).
#include <gtest/gtest.h>

#include "cli_helpers.h"
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace
{
  /// The column @p name of the CSV table @p path.
  std::vector<double>
  column(const std::string &path, const std::string &name)
  {
    std::ifstream in(path);
    std::string   line;
    std::getline(in, line);
    std::vector<std::string> header;
    {
      std::istringstream h(line);
      std::string        cell;
      while (std::getline(h, cell, ','))
        header.push_back(cell);
    }
    unsigned int k = 0;
    while (k < header.size() && header[k] != name)
      ++k;
    EXPECT_LT(k, header.size()) << name << " not in " << path;
    std::vector<double> values;
    while (std::getline(in, line))
      {
        std::istringstream row(line);
        std::string        cell;
        for (unsigned int i = 0; i <= k && std::getline(row, cell, ','); ++i)
          ;
        values.push_back(std::stod(cell));
      }
    return values;
  }
} // namespace



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
      const std::string csv = cli::join(folder.path, "out/contact-0001.csv");
      const auto        recovered = column(csv, "recovered_pressure");
      const auto        pressure  = column(csv, "pressure");
      ASSERT_FALSE(recovered.empty());
      for (unsigned int i = 0; i < recovered.size(); ++i)
        {
          EXPECT_NEAR(recovered[i], 1., 1e-8) << "pair " << i;
          EXPECT_NEAR(pressure[i], 1., 1e-8) << "pair " << i;
        }
    }
}
