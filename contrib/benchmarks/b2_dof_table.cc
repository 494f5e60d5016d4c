// b2_dof_table: see `usage` below (also printed by --help).

#include <igabde/base/utilities.h>

#include <igabde/nurbs/geometry_builders.h>
#include <igabde/nurbs/parametric_mesh.h>

#include <deal.II/base/mpi.h>

#include <deal.II/grid/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>

#include "option_value.h"
#include <array>
#include <iostream>

namespace
{
  const char *const usage =
    R"(Element count against unknowns for the five meshes of the curved-beam
scene B2 (scenes.md): quadratic NURBS (control points of the curved-beam
patch after degree elevation and knot insertion), FE_Q(2) (a DoFHandler on
the same knot-span mesh) and the 20-node serendipity count of ANSYS SOLID95
(vertices plus edges of that mesh). Per beam and for the two beams.
)";
} // namespace

int
main(int argc, char **argv)
{
  igabde::benchmarks::answer_help(argc, argv, usage);
  // MUMPS (the direct solver) runs on MPI_COMM_SELF.
  const igabde::base::LightMpiSingleton    light_mpi_singleton;
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  using namespace dealii;
  using namespace igabde;
  const std::array<std::array<unsigned int, 3>, 5> meshes = {
    {{{2, 2, 2}}, {{4, 4, 4}}, {{8, 8, 8}}, {{8, 16, 8}}, {{8, 32, 8}}}};

  std::cout << "| mesh (r x theta x y) | elements per beam | NURBS p=2 DOFs | "
               "FE_Q(2) DOFs | 20-node serendipity DOFs |\n"
               "|---|---|---|---|---|\n";
  for (const auto &n : meshes)
    {
      // Outer beam of B2 (radii 5..6); the inner beam has the same counts.
      auto patch = nurbs::make_curved_beam(5., 6., 1.);
      nurbs::elevate_to_degree(patch, 2);
      nurbs::subdivide(patch, n);
      const unsigned int n_nurbs = 3 * patch.n_control_points();

      Triangulation<3> triangulation;
      nurbs::make_parametric_triangulation(patch, triangulation);
      DoFHandler<3> dof_handler(triangulation);
      dof_handler.distribute_dofs(FESystem<3>(FE_Q<3>(2), 3));
      const unsigned int n_lagrange = dof_handler.n_dofs();
      const unsigned int n_serendipity =
        3 * (triangulation.n_vertices() + triangulation.n_active_lines());

      std::cout << "| " << n[0] << "x" << n[1] << "x" << n[2] << " | "
                << triangulation.n_active_cells() << " | " << n_nurbs << " ("
                << 2 * n_nurbs << ") | " << n_lagrange << " (" << 2 * n_lagrange
                << ") | " << n_serendipity << " (" << 2 * n_serendipity
                << ") |\n";
    }
  std::cout << "\nCounts per beam, the two beams in parentheses.\n";
}
