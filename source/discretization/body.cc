#include <igabde/base/utilities.h>
#include <igabde/linear_algebra/sparse_cholesky.h>

#include <igabde/discretization/body.h>
#include <igabde/discretization/body_description.h>
#include <igabde/discretization/body_linear_solver.h>
#include <igabde/discretization/iga_body.h>
#include <igabde/discretization/lagrange_body.h>

#include <deal.II/base/array_view.h>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/thread_management.h>
#include <deal.II/base/timer.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <exception>
#include <iomanip>
#include <ostream>
#include <utility>

namespace igabde
{
  namespace discretization
  {
    template <int dim>
    Tensor<1, dim>
    PointOperator<dim>::displacement(const Vector<double> &u) const
    {
      Tensor<1, dim> result;
      for (unsigned int k = 0; k < weights.size(); ++k)
        for (unsigned int c = 0; c < dim; ++c)
          result[c] += weights[k] * u[dofs[k][c]];
      return result;
    }



    template <int dim>
    void
    PointOperator<dim>::distribute(const Tensor<1, dim> &force,
                                   Vector<double>       &f) const
    {
      for (unsigned int k = 0; k < weights.size(); ++k)
        for (unsigned int c = 0; c < dim; ++c)
          f[dofs[k][c]] += weights[k] * force[c];
    }



    template <int dim>
    Body<dim>::Body(const BodyDescription<dim>   &description,
                    const DiscretizationSettings &settings)
      : settings(settings)
      , body_description(std::make_unique<BodyDescription<dim>>(description))
      , linear_solver(std::make_unique<LinearSolver>())
    {
      description.material.validate("Body '" + description.name + "'");
    }



    template <int dim>
    Body<dim>::~Body() = default;



    template <int dim>
    void
    Body<dim>::setup()
    {
      setup_system();
      factorize();
    }



    template <int dim>
    void
    Body<dim>::setup_system()
    {
      setup_space();
      AssertDimension(dof_locations.size(), n_unknowns);
      AssertDimension(dof_components.size(), n_unknowns);
      assembled       = false;
      assembled_share = false;
      if (shares_assembly())
        assemble_share();
      else if (layout.matrix_everywhere || factorizes_here())
        ensure_assembled();
      // K on the group's ranks only, unless the layout puts it everywhere
      // (a later ensure_assembled() on every rank does).
      assembled_everywhere = layout.matrix_everywhere;
      find_free_rigid_modes();
      hold_rotations();
    }



    template <int dim>
    void
    Body<dim>::set_parallel_layout(const ParallelLayout &new_layout)
    {
      layout = new_layout;
    }



    template <int dim>
    void
    Body<dim>::ensure_assembled()
    {
      assembled_everywhere = true;
      if (assembled && !assembled_share)
        return;
      assemble();
      assembled       = true;
      assembled_share = false;
      matrix_entries  = sparsity.n_nonzero_elements();
      check_load_magnitudes();
    }



    template <int dim>
    bool
    Body<dim>::shares_assembly() const
    {
      return factorizes_here() && !layout.matrix_everywhere &&
             settings.linear_solver == discretization::LinearSolver::direct &&
             Utilities::MPI::n_mpi_processes(layout.group) > 1;
    }



    template <int dim>
    void
    Body<dim>::assemble_share()
    {
      // Contiguous runs of the cells, as the VTU pieces; the share that
      // starts at the first cell also adds the point loads and moments.
      assembly_cells =
        output_cells(Utilities::MPI::this_mpi_process(layout.group),
                     Utilities::MPI::n_mpi_processes(layout.group));
      assemble();
      assembly_cells  = {0, std::numeric_limits<unsigned int>::max()};
      assembled       = true;
      assembled_share = true;
      matrix_entries  = sparsity.n_nonzero_elements();
      for (auto &f : history_rhs)
        Utilities::MPI::sum(ArrayView<const double>(f.data(), f.size()),
                            layout.group,
                            ArrayView<double>(f.data(), f.size()));
      if (!history_rhs.empty())
        load_rhs = history_rhs[0];
      check_load_magnitudes();
    }



    template <int dim>
    void
    Body<dim>::check_load_magnitudes() const
    {
      const double limit = base::largest_squarable_entry(n_unknowns);
      for (unsigned int h = 0; h < history_rhs.size(); ++h)
        {
          const double largest = base::largest_magnitude(history_rhs[h].data(),
                                                         history_rhs[h].size());
          if (largest <= limit)
            continue;
          const std::string &name = description().name;
          const std::string  section =
            name.rfind("body", 0) == 0 ? "Body " + name.substr(4) : name;
          const std::string history =
            h == 0 ? "Load path/Load factors" :
            h == 1 ? "Load path/Displacement factors" :
                     "load history " + std::to_string(h - 1) +
                       " of Load path/Histories";
          AssertThrow(false,
                      base::ExcInput(
                        section + ": the loads that follow " + history +
                        (std::isfinite(largest) ?
                           " reach " + base::number_text(largest) +
                             ", past the " + base::number_text(limit) +
                             " whose square double precision can hold" :
                           " are not finite") +
                        ": no solve has an answer; check the magnitudes "
                        "(and units) of " +
                        section +
                        "/Tractions, Body force, Point loads and Moments"));
        }
    }



    template <int dim>
    Vector<double>
    Body<dim>::stiffness_times(const Vector<double> &u) const
    {
      Vector<double> Ku(n_unknowns);
      system_matrix.vmult(Ku, u);
      if (assembled_share)
        Utilities::MPI::sum(ArrayView<const double>(Ku.data(), Ku.size()),
                            layout.group,
                            ArrayView<double>(Ku.data(), Ku.size()));
      return Ku;
    }



    template <int dim>
    std::size_t
    Body<dim>::n_matrix_entries() const
    {
      return matrix_entries;
    }



    template <int dim>
    void
    Body<dim>::share_assembly()
    {
      if (Utilities::MPI::n_mpi_processes(layout.world) == 1)
        return;
      unsigned int n_h = history_rhs.size();
      Utilities::MPI::broadcast(&n_h, 1, layout.root, layout.world);
      history_rhs.resize(n_h, Vector<double>(n_unknowns));
      for (auto &f : history_rhs)
        Utilities::MPI::broadcast(f.data(),
                                  f.size(),
                                  layout.root,
                                  layout.world);
      if (n_h > 0)
        load_rhs = history_rhs[0];
      check_load_magnitudes();
      unsigned long long entries = matrix_entries;
      Utilities::MPI::broadcast(&entries, 1, layout.root, layout.world);
      matrix_entries = entries;
    }



    template <int dim>
    bool
    Body<dim>::factorizes_here() const
    {
      return layout.group != MPI_COMM_NULL;
    }



    template <int dim>
    bool
    Body<dim>::contains(const Point<dim> &location) const
    {
      try
        {
          point_operator(location);
          return true;
        }
      catch (const ExceptionBase &)
        {
          return false;
        }
    }



    template <int dim>
    unsigned int
    Body<dim>::dof_component(const types::global_dof_index i) const
    {
      AssertIndexRange(i, dof_components.size());
      return dof_components[i];
    }



    template <int dim>
    const Point<dim> &
    Body<dim>::dof_location(const types::global_dof_index i) const
    {
      AssertIndexRange(i, dof_locations.size());
      return dof_locations[i];
    }



    template <int dim>
    Tensor<1, dim>
    Body<dim>::support_reaction(const Vector<double> &u,
                                const Vector<double> &f) const
    {
      AssertDimension(u.size(), n_unknowns);
      AssertDimension(f.size(), n_unknowns);
      // Under a parallel layout the root computes it (every rank has the
      // same u and f) and hands it to all; K u comes from the root's K, or
      // from the group's shares when the group divided the assembly.
      std::array<double, dim> reaction{};
      const bool              root =
        (Utilities::MPI::this_mpi_process(layout.world) == layout.root);
      if (root || assembled_share)
        {
          Vector<double> r = restoring_force(u);
          r -= f;
          if (root)
            for (types::global_dof_index i = 0; i < n_unknowns; ++i)
              if (constraints.is_constrained(i))
                reaction[dof_components[i]] += r[i];
        }
      if (Utilities::MPI::n_mpi_processes(layout.world) > 1)
        Utilities::MPI::broadcast(reaction.data(),
                                  dim,
                                  layout.root,
                                  layout.world);
      Tensor<1, dim> result;
      for (unsigned int c = 0; c < dim; ++c)
        result[c] = reaction[c];
      return result;
    }



    template <int dim>
    std::vector<double>
    Body<dim>::face_motion_reaction(const Vector<double>      &u,
                                    const Vector<double>      &f,
                                    const unsigned int         k,
                                    const std::vector<double> &factors) const
    {
      AssertIndexRange(k, description().face_motions.size());
      const FaceMotion<dim> &motion = description().face_motions[k];
      const unsigned int     n_axes = (dim == 2 ? 1 : 3);
      std::vector<double>    result(dim + n_axes, 0.);
      const bool             root =
        (Utilities::MPI::this_mpi_process(layout.world) == layout.root);
      if (root || assembled_share)
        {
          // K u: collective on the group when it divided the assembly; the
          // root alone sums the reactions.
          Vector<double> r = restoring_force(u);
          r -= f;
          // At finite strain the moment arms are those of the moved points
          // about the moved centroid: x - c' = R (X - c) on the face.
          Tensor<2, dim> R = unit_symmetric_tensor<dim>();
          if (finite_strain())
            {
              const unsigned int h =
                description().dirichlet.at(motion.condition).history;
              R = motion.exact_rotation(h < factors.size() ? factors[h] : 0.);
            }
          if (root)
            for (const types::global_dof_index i :
                 dirichlet_dofs.at(motion.condition))
              {
                const unsigned int   c = dof_components[i];
                const Tensor<1, dim> y =
                  finite_strain() ? R * (dof_locations[i] - motion.centre) :
                                    dof_locations[i] - motion.centre;
                result[c] += r[i];
                // The moment of the force r_i e_c at y: (y x e_c) r_i.
                if (dim == 2)
                  result[dim] += (c == 1 ? y[0] : -y[1]) * r[i];
                else
                  for (unsigned int a = 0; a < 3; ++a)
                    if (a != c)
                      result[dim + a] +=
                        ((c == (a + 2) % 3) ? y[(a + 1) % 3] :
                                              -y[(a + 2) % 3]) *
                        r[i];
              }
        }
      if (Utilities::MPI::n_mpi_processes(layout.world) > 1)
        Utilities::MPI::broadcast(result.data(),
                                  result.size(),
                                  layout.root,
                                  layout.world);
      return result;
    }



    template <int dim>
    const SparseMatrix<double> &
    Body<dim>::stiffness_matrix() const
    {
      Assert(assembled && !assembled_share,
             ExcMessage("K is not assembled on this rank."));
      AssertThrow(!reduced_to_reaction_rows,
                  ExcMessage("K was reduced to its reaction rows "
                             "(keep_reaction_rows_only())."));
      return system_matrix;
    }



    template <int dim>
    bool
    Body<dim>::is_held(const types::global_dof_index i) const
    {
      return solve_constraints.is_constrained(i);
    }



    template <int dim>
    bool
    Body<dim>::is_supported(const types::global_dof_index i) const
    {
      return constraints.is_constrained(i);
    }



    template <int dim>
    types::global_dof_index
    Body<dim>::n_dofs() const
    {
      return n_unknowns;
    }



    template <int dim>
    const BodyDescription<dim> &
    Body<dim>::description() const
    {
      return *body_description;
    }



    template <int dim>
    const std::string &
    Body<dim>::name() const
    {
      return body_description->name;
    }



    template <int dim>
    const elasticity::IsotropicMaterial<dim> &
    Body<dim>::material() const
    {
      return body_description->material;
    }



    template <int dim>
    const Vector<double> &
    Body<dim>::load_solution() const
    {
      return u_history[0];
    }



    template <int dim>
    const Vector<double> &
    Body<dim>::prescribed_solution() const
    {
      return u_history[1];
    }



    template <int dim>
    const Vector<double> &
    Body<dim>::load_vector() const
    {
      return load_rhs;
    }



    template <int dim>
    unsigned int
    Body<dim>::n_histories() const
    {
      return history_rhs.size();
    }



    template <int dim>
    const Vector<double> &
    Body<dim>::history_solution(const unsigned int h) const
    {
      AssertIndexRange(h, u_history.size());
      return u_history[h];
    }



    template <int dim>
    const Vector<double> &
    Body<dim>::history_load_vector(const unsigned int h) const
    {
      AssertIndexRange(h, history_rhs.size());
      return history_rhs[h];
    }



    template <int dim>
    Vector<double>
    Body<dim>::external_solution(const std::vector<double> &factors) const
    {
      Vector<double> u(n_unknowns);
      for (unsigned int h = 0; h < u_history.size() && h < factors.size(); ++h)
        u.add(factors[h], u_history[h]);
      return u;
    }



    template <int dim>
    Vector<double>
    Body<dim>::external_load_vector(const std::vector<double> &factors) const
    {
      Vector<double> f(n_unknowns);
      for (unsigned int h = 0; h < history_rhs.size() && h < factors.size();
           ++h)
        f.add(factors[h], history_rhs[h]);
      return f;
    }



    template <int dim>
    void
    Body<dim>::assemble_history_loads(
      const std::function<void(const elasticity::BodyForce<dim> &,
                               const std::vector<NeumannCondition<dim>> &,
                               SparseMatrix<double> &,
                               Vector<double> &)> &assemble,
      const std::function<void(const PointLoad<dim> &, Vector<double> &)>
        &point_load)
    {
      const BodyDescription<dim> &d   = description();
      const unsigned int          n_h = d.n_histories();
      history_rhs.assign(n_h, Vector<double>(n_unknowns));
      SparseMatrix<double> scratch;
      for (unsigned int h = 0; h < n_h; ++h)
        {
          // At finite strain a pressure follows the surface: it is no
          // load case (add_follower_pressure()).
          std::vector<NeumannCondition<dim>> tractions;
          for (const auto &t : d.tractions)
            if (t.history == h && !(finite_strain() && t.pressure))
              tractions.push_back(t);
          if (h == 0)
            {
              system_matrix.reinit(sparsity);
              assemble(elasticity::BodyForce<dim>{d.body_force,
                                                  d.body_force_field},
                       tractions,
                       system_matrix,
                       history_rhs[h]);
            }
          else if (!tractions.empty())
            {
              // The tractions' loads only (an empty matrix: no stiffness).
              assemble(elasticity::BodyForce<dim>(),
                       tractions,
                       scratch,
                       history_rhs[h]);
            }
          // Point loads and moments once: by the rank whose cells start at
          // the first (all of them unless the group divides the assembly).
          if (assembly_cells.first > 0)
            continue;
          for (const auto &load : d.point_loads)
            if (load.history == h)
              point_load(load, history_rhs[h]);
          // A moment M on a face: the loads sum_a alpha_a c_a of the
          // tractions alpha_a e_a x (x - x_c), whose moment J alpha is M.
          for (const auto &moment : d.moments)
            if (moment.history == h)
              {
                std::vector<Vector<double>> c;
                FullMatrix<double>          J, J_inverse;
                face_rotation_loads(moment.boundary_id, c, J);
                AssertDimension(moment.moment.size(), c.size());
                J_inverse.reinit(J.m(), J.n());
                J_inverse.invert(J);
                for (unsigned int a = 0; a < c.size(); ++a)
                  {
                    double alpha = 0.;
                    for (unsigned int b = 0; b < c.size(); ++b)
                      alpha += J_inverse(a, b) * moment.moment[b];
                    history_rhs[h].add(alpha, c[a]);
                  }
              }
        }
      load_rhs = history_rhs[0];
    }



    template <int dim>
    void
    Body<dim>::set_progress_stream(std::ostream *stream)
    {
      progress_stream = stream;
    }



    template <int dim>
    void
    Body<dim>::move_surfaces(const Vector<double> &u) const
    {
      AssertDimension(u.size(), n_dofs());
      Assert(surfaces_mover.load() == std::thread::id() || surfaces_moved(),
             ExcMessage("move_surfaces() from two threads"));
      // The moved geometry first; then this thread's queries use it.
      move_surface_geometry(&u);
      surfaces_mover.store(std::this_thread::get_id());
    }



    template <int dim>
    void
    Body<dim>::reset_surfaces() const
    {
      if (!surfaces_moved())
        return;
      surfaces_mover.store(std::thread::id());
      move_surface_geometry(nullptr);
    }



    template <int dim>
    bool
    Body<dim>::surfaces_moved() const
    {
      return surfaces_mover.load() == std::this_thread::get_id();
    }



    template <int dim>
    SurfacePoint<dim>
    Body<dim>::closest_surface_point(const types::boundary_id,
                                     const Point<dim>        &location,
                                     const SurfacePoint<dim> &nearest) const
    {
      // The point location below searches the reference mesh.
      Assert(!surfaces_moved(),
             ExcMessage("closest_surface_point() of " + name() +
                        " on a moved configuration: pair it by the weighted "
                        "gap, which projects through face_point()"));
      SurfacePoint<dim> result = nearest;
      result.tributary_area    = 0.;
      const Point<dim> projected =
        location -
        ((location - nearest.location) * nearest.normal) * nearest.normal;
      try
        {
          result.op       = point_operator(projected);
          result.location = projected;
        }
      catch (const ExceptionBase &)
        {
          // The projection left a curved face: keep the nearest point.
        }
      return result;
    }



    template <int dim>
    std::unique_ptr<Body<dim>>
    create_body(const BodyDescription<dim>   &description,
                const DiscretizationSettings &settings)
    {
      if (settings.type == Type::nurbs)
        return std::make_unique<IgaBody<dim>>(description, settings);
      return std::make_unique<LagrangeBody<dim>>(description, settings);
    }



    template struct PointOperator<2>;
    template struct PointOperator<3>;
    template class Body<2>;
    template class Body<3>;
    template std::unique_ptr<Body<2>>
    create_body(const BodyDescription<2> &, const DiscretizationSettings &);
    template std::unique_ptr<Body<3>>
    create_body(const BodyDescription<3> &, const DiscretizationSettings &);
  } // namespace discretization
} // namespace igabde
