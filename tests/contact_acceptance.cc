// Acceptance of the contact layer on the verification scenes V3, V4, V5
// and the benchmark B2 (doc/scenes.md), for NURBS and Lagrange: each line
// states a criterion of the contact issue and whether the run met it, with the
// measured figure rounded so that the comparison is stable.

#include "tests.h"

#include <igabde/base/utilities.h>

#include <igabde/scene/simulator.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

using namespace igabde;

namespace
{
  nlohmann::json
  run(const std::string                               &scene,
      const std::string                               &tag,
      std::vector<std::pair<std::string, std::string>> overrides)
  {
    overrides.emplace_back("Output/Directory", "output-" + tag);
    overrides.emplace_back("Output/Write vtu", "false");
    overrides.emplace_back("Output/Print timing", "false");
    std::ostringstream log;
    return scene::run_scene_in_process((std::filesystem::path(SOURCE_DIR) /
                                        ".." / "prm" / (scene + ".prm"))
                                         .string(),
                                       overrides,
                                       log);
  }

  const char *
  yes(const bool b)
  {
    return b ? "yes" : "NO";
  }
} // namespace



int
main(int argc, char **argv)
{
  // MUMPS (the direct solver) runs on MPI_COMM_SELF.
  const igabde::base::LightMpiSingleton    light_mpi_singleton;
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  initlog();

  // V3: every pair's pressure equals the applied pressure to 1e-8, and with
  // friction no tangential force is transmitted (the exact state is
  // uniaxial stress: the identical blocks expand alike, so the stick
  // solution has zero tangential force). Without friction there are no
  // tangential unknowns and the tangential resultant is zero by
  // construction: not printed. The total normal force is not a check
  // either: the upper block is held only by the contact, whose equilibrium
  // equation G^T p = b makes it equal the load by construction.
  for (const std::string dim : {"2d", "3d"})
    for (const std::string type : {"nurbs", "lagrange"})
      for (const std::string mu : {"0", "0.3"})
        {
          const auto   summary = run("v3-contact-patch-" + dim,
                                   "v3-" + dim + type + mu,
                                   {{"Discretization/Type", type},
                                      {"Contact/Friction coefficient", mu}});
          const double u =
            summary.at("checks").at("pressure_uniformity").get<double>();
          const auto &f =
            summary.at("load_steps").at(0).at("total_contact_force");
          double tangential = 0.;
          for (unsigned int d = 0; d + 1 < f.size(); ++d)
            tangential = std::max(tangential, std::abs(f.at(d).get<double>()));
          deallog << "V3 " << dim << " " << type << " mu=" << mu << ": pairs "
                  << summary.at("n_contact_pairs").get<double>()
                  << ", pressure uniformity <= 1e-8: " << yes(u <= 1e-8);
          if (mu != "0")
            deallog << ", tangential resultant <= 1e-8: "
                    << yes(tangential <= 1e-8);
          deallog << std::endl;
        }

  // V3 on non-matching surfaces (the lower block split 3 x 3): the pairs
  // use the closest point of the master face; the pressure is not uniform
  // (node-to-surface pairs do not pass the patch test) and the resultant
  // equals the load by construction (the upper block floats), so what is
  // checked is that the solve converges and its answer passes the
  // post-solve contact-condition check (status ok).
  for (const std::string type : {"nurbs", "lagrange"})
    {
      const auto summary =
        run("v3-contact-patch-2d",
            "v3-nonmatching-" + type,
            {{"Discretization/Type", type}, {"Body 2/Subdivisions", "3"}});
      deallog << "V3 non-matching " << type
              << ": solved, contact conditions hold: "
              << yes(summary.at("status").get<std::string>() == "ok")
              << std::endl;
    }

  // V4: stick pairs in the stick phase; once the block slides, every pair
  // slips the same way, so the resultant sits on the cone, |F_t| = mu |F_n|.
  // (That the resultant never leaves the cone follows from the per-pair
  // law, which the post-solve check holds; it is not restated here.)
  for (const std::string type : {"nurbs", "lagrange"})
    {
      const auto summary =
        run("v4-sliding-block", "v4-" + type, {{"Discretization/Type", type}});
      const auto  &steps     = summary.at("load_steps");
      const double mu        = 0.4;
      bool         saw_stick = false;
      for (unsigned int s = 1; s < steps.size(); ++s)
        saw_stick = saw_stick || steps.at(s).at("n_stick").get<double>() > 0;
      const auto  &f = steps.at(steps.size() - 1).at("total_contact_force");
      const double last_ratio = std::abs(f.at(0).get<double>()) /
                                (mu * std::abs(f.at(1).get<double>()));
      deallog << "V4 " << type << ": " << steps.size()
              << " steps, stick pairs while sticking: " << yes(saw_stick)
              << ", sliding |F_t| = mu |F_n| to 1e-8: "
              << yes(std::abs(last_ratio - 1.) <= 1e-8) << std::endl;
    }

  // V4 reversed and unloaded (hard case "a load step that unloads"): the
  // top goes to +0.05, back to -0.025, then the pressure is halved; the
  // friction force follows the slip direction and stays on the cone.
  {
    const auto summary =
      run("v4-sliding-block",
          "v4-reversal",
          {{"Load path/Load factors", "1, 1, 1, 1, 1, 0.5"},
           {"Load path/Displacement factors", "0, 0.5, 1, 0, -0.5, -0.5"}});
    const auto  &steps = summary.at("load_steps");
    const double mu    = 0.4;
    auto         ratio = [&](const unsigned int s) {
      const auto &f = steps.at(s).at("total_contact_force");
      return f.at(0).get<double>() / (mu * f.at(1).get<double>());
    };
    deallog << "V4 reversal: forward slip F_t = -mu F_n: "
            << yes(std::abs(ratio(2) + 1.) <= 1e-8)
            << ", backward slip F_t = +mu F_n: "
            << yes(std::abs(ratio(4) - 1.) <= 1e-8)
            << ", after halving the pressure F_t = +mu F_n: "
            << yes(std::abs(ratio(5) - 1.) <= 1e-8) << std::endl;
  }

  // V5 Hertz. Half-width: the edge of the contact zone lies between the
  // last loaded and the first open pair, and the estimate is kept in that
  // interval, so a pair-resolved a is known to one pair spacing h there
  // (checks.hertz_edge_pair_spacing). The reference is a converged model of
  // the same finite half-disc by the other discretisation (two uniform
  // refinements; its own a is known to its spacing h_ref), since the
  // half-disc is not Johnson's half-space. Profile: L2 distance to
  // Johnson's p(x) <= 3 % (the finite disc's floor is about 1 %).
  for (const std::string type : {"nurbs", "lagrange"})
    {
      const std::string other = type == "nurbs" ? "lagrange" : "nurbs";
      const auto        summary =
        run("v5-hertz-2d", "v5-" + type, {{"Discretization/Type", type}});
      const auto   reference = run("v5-hertz-2d",
                                 "v5-reference-" + other,
                                 {{"Discretization/Type", other},
                                    {"Discretization/Refinements", "2"}});
      const auto  &checks    = summary.at("checks");
      const double a_h       = checks.at("hertz_half_width").get<double>();
      const double h  = checks.at("hertz_edge_pair_spacing").get<double>();
      const double l2 = checks.at("pressure_l2_rel_error").get<double>();
      const double a_ref =
        reference.at("checks").at("hertz_half_width").get<double>();
      const double h_ref =
        reference.at("checks").at("hertz_edge_pair_spacing").get<double>();
      deallog << "V5 " << type
              << ": half-width within one edge pair spacing of the refined "
              << other << " model's: "
              << yes(h > 0. && h_ref > 0. && std::abs(a_h - a_ref) <= h + h_ref)
              << ", profile L2 error <= 3 %: " << yes(l2 <= 0.03)
              << ", half-width " << std::setprecision(3) << a_h
              << std::setprecision(6) << std::endl;
    }

  // B2 (the scene's 4 x 4 x 4 per beam, as its scene tests run it) against
  // a converged model of the same scene by a higher degree: NURBS p = 3 on
  // 8 x 16 x 8. Error measure: the largest |u_z - u_z,ref| over the probes
  // A-D over the largest |u_z,ref|. The bound is the a-posteriori estimate
  // of the same discretisation one uniform refinement finer: where the
  // error falls at least as h^2 (2 is the rate's floor the argument needs;
  // the probe displacements converge faster on these meshes),
  // |u_h - u| <= |u_h - u_h/2| / (1 - 2^-2) = 4/3 |u_h - u_h/2| and
  // |u_h/2 - u| <= 1/3 |u_h - u_h/2|. The reference's own error is bounded
  // the same way, by 1/3 of its change from p = 3 on 4 x 8 x 4, and added;
  // it must be a tenth of the bounds it serves, or the reference is not
  // converged enough to check them. A line fails when a discretisation
  // converges to another limit than the reference, or more slowly than h^2.
  {
    const std::vector<std::string> probes = {"A", "B", "C", "D"};
    const auto uz = [&](const nlohmann::json &summary, const std::string &p) {
      return summary.at("points").at(p).at(2).get<double>();
    };
    const auto mesh_run = [&](const std::string &tag,
                              const std::string &type,
                              const std::string &degree,
                              const std::string &mesh) {
      return run("b2-curved-beams",
                 tag,
                 {{"Discretization/Type", type},
                  {"Discretization/Degree", degree},
                  {"Body 1/Subdivisions", mesh},
                  {"Body 2/Subdivisions", mesh}});
    };
    const auto reference = mesh_run("b2-ref", "nurbs", "3", "8, 16, 8");
    const auto reference_coarse =
      mesh_run("b2-ref-coarse", "nurbs", "3", "4, 8, 4");
    double scale = 0.;
    for (const auto &p : probes)
      scale = std::max(scale, std::abs(uz(reference, p)));
    const auto distance = [&](const nlohmann::json &a,
                              const nlohmann::json &b) {
      double d = 0.;
      for (const auto &p : probes)
        d = std::max(d, std::abs(uz(a, p) - uz(b, p)));
      return d / scale;
    };
    const double uncertainty = distance(reference, reference_coarse) / 3.;
    for (const std::string type : {"nurbs", "lagrange"})
      {
        const auto coarse = mesh_run("b2-" + type + "-4", type, "2", "4, 4, 4");
        const auto fine   = mesh_run("b2-" + type + "-8", type, "2", "8, 8, 8");
        const double d    = distance(coarse, fine);
        deallog << "B2 " << type
                << " p=2: 4x4x4 within 4/3 of its distance to 8x8x8 from "
                   "the p=3 8x16x8 model: "
                << yes(distance(coarse, reference) <= 4. / 3. * d + uncertainty)
                << ", 8x8x8 within 1/3: "
                << yes(distance(fine, reference) <= d / 3. + uncertainty)
                << ", the reference's error below a tenth of these bounds: "
                << yes(uncertainty <= 0.1 * d / 3.) << std::endl;
      }
  }
}
