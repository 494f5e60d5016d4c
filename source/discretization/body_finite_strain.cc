#include <igabde/base/utilities.h>

#include <igabde/discretization/body.h>
#include <igabde/discretization/body_description.h>

#include <deal.II/base/exceptions.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

// The finite-strain questions of a body (Body, "Finite strain"): its law,
// the force of its stress, the follower pressures and the supports' values
// with the exact rotations of the face motions.

namespace igabde
{
  namespace discretization
  {

    template <int dim>
    bool
    Body<dim>::finite_strain() const
    {
      return body_description->kinematics == elasticity::Kinematics::finite;
    }



    template <int dim>
    elasticity::HyperelasticMaterial<dim>
    Body<dim>::finite_law() const
    {
      AssertThrow(finite_strain(),
                  ExcMessage("Body '" + name() +
                             "' is modelled at small strain; it has no "
                             "finite-strain law."));
      return elasticity::HyperelasticMaterial<dim>(body_description->model,
                                                   body_description->material);
    }



    template <int dim>
    Vector<double>
    Body<dim>::restoring_force(const Vector<double> &u) const
    {
      if (!finite_strain())
        {
          AssertThrow(assembled, ExcInternalError());
          return stiffness_times(u);
        }
      Vector<double> force(n_unknowns);
      const double   min_J = internal_force(u, finite_law(), force, nullptr);
      AssertThrow(min_J > 0.,
                  ExcMessage("Body '" + name() +
                             "': det F <= 0 at a quadrature point: an "
                             "element has inverted."));
      return force;
    }



    template <int dim>
    std::vector<std::pair<types::boundary_id, double>>
    Body<dim>::follower_pressures(const std::vector<double> &factors) const
    {
      std::vector<std::pair<types::boundary_id, double>> pressures;
      if (finite_strain())
        for (const auto &t : description().tractions)
          if (t.pressure)
            pressures.emplace_back(t.boundary_id,
                                   (t.history < factors.size() ?
                                      factors[t.history] :
                                      0.) *
                                     *t.pressure);
      return pressures;
    }



    template <int dim>
    Vector<double>
    Body<dim>::applied_loads(const Vector<double>      &u,
                             const std::vector<double> &factors) const
    {
      Vector<double> f = external_load_vector(factors);
      if (follower_pressures(factors).empty())
        return f;
      // The follower loads enter the residual f_int - f_ext with their sign
      // reversed.
      Vector<double> residual(n_unknowns);
      add_follower_pressure(u, factors, residual, nullptr);
      f -= residual;
      return f;
    }



    template <int dim>
    SymmetricTensor<2, dim>
    Body<dim>::point_stress(const Vector<double> &u,
                            const Point<dim>     &location) const
    {
      return finite_strain() ? cauchy_stress(u, location, finite_law()) :
                               stress(u, location);
    }



    template <int dim>
    const SparsityPattern &
    Body<dim>::sparsity_pattern() const
    {
      return sparsity;
    }



    template <int dim>
    const AffineConstraints<double> &
    Body<dim>::support_constraints() const
    {
      return constraints;
    }



    template <int dim>
    SymmetricTensor<2, dim>
    Body<dim>::cauchy_stress(
      const Vector<double>                        &u,
      const Point<dim>                            &location,
      const elasticity::HyperelasticMaterial<dim> &material) const
    {
      const Tensor<2, dim> F = elasticity::deformation_gradient<dim>(
        displacement_gradient(u, location));
      AssertThrow(determinant(F) > 0.,
                  ExcMessage("Body '" + description().name +
                             "': det F <= 0 at (" + base::to_string(location) +
                             "): the element has inverted there."));
      return elasticity::cauchy_stress(F,
                                       material.second_piola_kirchhoff(
                                         elasticity::right_cauchy_green(F)));
    }



    template <int dim>
    Vector<double>
    Body<dim>::prescribed_values(const std::vector<double> &factors) const
    {
      Vector<double> g(n_unknowns);
      for (types::global_dof_index i = 0; i < n_unknowns; ++i)
        if (prescribed_constraints.is_constrained(i))
          {
            const auto         it = prescribed_history.find(i);
            const unsigned int h =
              (it != prescribed_history.end() ? it->second : 1u);
            g[i] = (h < factors.size() ? factors[h] : 0.) *
                   prescribed_constraints.get_inhomogeneity(i);
          }
      if (!finite_strain())
        return g;
      // A face motion at finite strain: u = f d + (R(f r) - I)(x - c), the
      // exact rotation instead of the linear f r x (x - c). A linear field
      // in x takes the values of the field at the control points (the
      // rational basis sums to one), so the face turns rigidly.
      for (const FaceMotion<dim> &motion : description().face_motions)
        {
          const unsigned int h =
            description().dirichlet.at(motion.condition).history;
          const double         f = (h < factors.size() ? factors[h] : 0.);
          const Tensor<2, dim> R = motion.exact_rotation(f);
          for (const types::global_dof_index i :
               dirichlet_dofs.at(motion.condition))
            {
              const unsigned int   c = dof_components[i];
              const Tensor<1, dim> y = dof_locations[i] - motion.centre;
              g[i] = f * motion.displacement[c] + (R * y)[c] - y[c];
            }
        }
      return g;
    }



    template bool
    Body<2>::finite_strain() const;
    template bool
    Body<3>::finite_strain() const;
    template elasticity::HyperelasticMaterial<2>
    Body<2>::finite_law() const;
    template elasticity::HyperelasticMaterial<3>
    Body<3>::finite_law() const;
    template Vector<double>
    Body<2>::restoring_force(const Vector<double> &u) const;
    template Vector<double>
    Body<3>::restoring_force(const Vector<double> &u) const;
    template std::vector<std::pair<types::boundary_id, double>>
    Body<2>::follower_pressures(const std::vector<double> &factors) const;
    template std::vector<std::pair<types::boundary_id, double>>
    Body<3>::follower_pressures(const std::vector<double> &factors) const;
    template Vector<double>
    Body<2>::applied_loads(const Vector<double>      &u,
                           const std::vector<double> &factors) const;
    template Vector<double>
    Body<3>::applied_loads(const Vector<double>      &u,
                           const std::vector<double> &factors) const;
    template SymmetricTensor<2, 2>
    Body<2>::point_stress(const Vector<double> &u,
                          const Point<2>       &location) const;
    template SymmetricTensor<2, 3>
    Body<3>::point_stress(const Vector<double> &u,
                          const Point<3>       &location) const;
    template const SparsityPattern &
    Body<2>::sparsity_pattern() const;
    template const SparsityPattern &
    Body<3>::sparsity_pattern() const;
    template const AffineConstraints<double> &
    Body<2>::support_constraints() const;
    template const AffineConstraints<double> &
    Body<3>::support_constraints() const;
    template SymmetricTensor<2, 2>
    Body<2>::cauchy_stress(
      const Vector<double>                      &u,
      const Point<2>                            &location,
      const elasticity::HyperelasticMaterial<2> &material) const;
    template SymmetricTensor<2, 3>
    Body<3>::cauchy_stress(
      const Vector<double>                      &u,
      const Point<3>                            &location,
      const elasticity::HyperelasticMaterial<3> &material) const;
    template Vector<double>
    Body<2>::prescribed_values(const std::vector<double> &factors) const;
    template Vector<double>
    Body<3>::prescribed_values(const std::vector<double> &factors) const;
  } // namespace discretization
} // namespace igabde
