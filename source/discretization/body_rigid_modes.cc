#include <igabde/base/utilities.h>

#include <igabde/discretization/body.h>
#include <igabde/discretization/body_description.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/quadrature_lib.h>

#include <Eigen/Dense>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

// The rigid modes of a body: those its supports leave free, the rotations
// a Hold rotation holds, and the loads that move or balance them.

namespace igabde
{
  namespace discretization
  {

    template <int dim>
    const std::vector<Vector<double>> &
    Body<dim>::free_rigid_modes() const
    {
      return rigid_modes.free_modes();
    }



    template <int dim>
    const std::vector<std::string> &
    Body<dim>::free_rigid_mode_names() const
    {
      return rigid_modes.free_mode_names();
    }



    template <int dim>
    bool
    Body<dim>::free_translation(const unsigned int c) const
    {
      return rigid_modes.free_translation(c);
    }



    template <int dim>
    void
    Body<dim>::find_free_rigid_modes()
    {
      rigid_modes = RigidModes<dim>(dof_locations, dof_components, constraints);

      // Pins: one unknown per free mode, independent there (RigidModes::
      // pins()). With balanced loads the pins carry no reaction, so the
      // pinned solve is a generalised inverse K^+ (method.md, "Bodies held
      // only through contact"). A rotation held later (hold_rotations())
      // keeps its pin: the pinned solve of loads balanced in that mode,
      // projected.
      //
      // In floating point a pin does carry a reaction: the round-off of the
      // whole body's balance, about 1e-12 of the load. On a contact pair
      // that reaction is one pair's force error, and divided by the pair's
      // area a pressure error (the corner pair of the 3D contact patch at
      // 20 000 pairs: 1.2e-6). The pins' choice therefore sees boundary
      // unknowns weighted by 1e-3 and interior ones by pin_preference()
      // (deepest first, then nearest the centroid), so that pins sit inside
      // the body, where their reaction spreads before it reaches a surface;
      // a body without interior unknowns keeps the plain choice.
      solve_constraints.clear();
      solve_constraints.copy_from(constraints);
      if (!rigid_modes.free_modes().empty())
        {
          AffineConstraints<double> pins;
          for (const auto i : rigid_modes.pins(pin_preference()))
            pins.add_line(i);
          pins.close();
          solve_constraints.merge(pins);
        }
      solve_constraints.close();
    }



    template <int dim>
    std::vector<double>
    Body<dim>::pin_preference() const
    {
      std::vector<double> weights(n_unknowns, 1.);
      if (on_boundary.size() != n_unknowns)
        return weights;
      // Breadth-first search from the boundary through K's pattern.
      constexpr unsigned int    unreached = static_cast<unsigned>(-1);
      std::vector<unsigned int> depth(n_unknowns, unreached);
      std::vector<types::global_dof_index> front, next;
      for (types::global_dof_index i = 0; i < n_unknowns; ++i)
        if (on_boundary[i])
          {
            depth[i] = 0;
            front.push_back(i);
          }
      unsigned int max_depth = 0;
      while (!front.empty())
        {
          next.clear();
          for (const auto i : front)
            for (auto entry = sparsity.begin(i); entry != sparsity.end(i);
                 ++entry)
              if (depth[entry->column()] == unreached)
                {
                  depth[entry->column()] = depth[i] + 1;
                  max_depth              = depth[i] + 1;
                  next.push_back(entry->column());
                }
          front.swap(next);
        }
      if (max_depth == 0)
        return weights;
      // Among equally deep unknowns (a plate one cell thick has one interior
      // layer), the one nearest the centroid: half a depth step at most.
      for (types::global_dof_index i = 0; i < n_unknowns; ++i)
        if (depth[i] == 0)
          weights[i] = 1e-3;
        else
          {
            const double closeness =
              1. - (dof_locations[i] - rigid_modes.centre()).norm() /
                     rigid_modes.size();
            weights[i] =
              1. + (std::min(depth[i], max_depth) + 0.5 * closeness) /
                     (max_depth + 1.);
          }
      return weights;
    }



    template <int dim>
    void
    Body<dim>::face_rotation_loads(const types::boundary_id     face,
                                   std::vector<Vector<double>> &c,
                                   FullMatrix<double>          &J) const
    {
      // Gauss points of the face (two more per direction than its degree:
      // the tractions below are linear in x on a curved face too, up to
      // the geometry's rational factor).
      const FaceGrid<dim>         grid = face_grid(face);
      const QGauss<1>             gauss(grid.degree + 2);
      std::vector<Point<dim - 1>> etas(1);
      std::vector<double>         weights(1, 1.);
      for (unsigned int d = 0; d < dim - 1; ++d)
        {
          std::vector<Point<dim - 1>> next_etas;
          std::vector<double>         next_weights;
          const auto                 &b = grid.breaks[d];
          for (unsigned int k = 0; k < etas.size(); ++k)
            for (unsigned int e = 0; e + 1 < b.size(); ++e)
              for (unsigned int q = 0; q < gauss.size(); ++q)
                {
                  Point<dim - 1> eta = etas[k];
                  const double   h   = b[e + 1] - b[e];
                  eta[d]             = b[e] + h * gauss.point(q)[0];
                  next_etas.push_back(eta);
                  next_weights.push_back(weights[k] * h * gauss.weight(q));
                }
          etas.swap(next_etas);
          weights.swap(next_weights);
        }
      std::vector<FacePoint<dim>> points;
      double                      area = 0.;
      Point<dim>                  centroid;
      for (unsigned int q = 0; q < etas.size(); ++q)
        {
          points.push_back(face_point(face, etas[q]));
          weights[q] *= points.back().measure;
          area += weights[q];
          centroid += weights[q] * points.back().location;
        }
      AssertThrow(area > 0.,
                  ExcMessage("Body '" + description().name + "': face " +
                             std::to_string(face) +
                             " has no area: no rotation or moment can act "
                             "on it."));
      centroid /= area;

      // One traction per rotation axis, t_a = e_a x (x - centroid): a pure
      // moment (zero resultant) whose consistent loads c_a are the
      // constraint's direction; J_ab = int (|y|^2 delta_ab - y_a y_b) is the
      // moment of t_a about axis b.
      const unsigned int n_axes = (dim == 2 ? 1 : 3);
      c.assign(n_axes, Vector<double>(n_unknowns));
      J.reinit(n_axes, n_axes);
      for (unsigned int q = 0; q < points.size(); ++q)
        {
          const Tensor<1, dim> y = points[q].location - centroid;
          for (unsigned int a = 0; a < n_axes; ++a)
            {
              Tensor<1, dim> t;
              if (dim == 2)
                {
                  t[0] = -y[1];
                  t[1] = y[0];
                }
              else
                {
                  const unsigned int b = (a + 1) % 3, d = (a + 2) % 3;
                  t[b] = -y[d];
                  t[d] = y[b];
                }
              points[q].op.distribute(weights[q] * t, c[a]);
              for (unsigned int b = 0; b < n_axes; ++b)
                J(a, b) += weights[q] * ((a == b ? y * y : 0.) -
                                         (dim == 2 ? 0. : y[a] * y[b]));
            }
        }
      for (auto &v : c)
        constraints.set_zero(v);
    }



    template <int dim>
    void
    Body<dim>::hold_rotations()
    {
      held_response.clear();
      const int face = description().hold_rotation_face;
      if (face < 0 || rigid_modes.free_modes().empty())
        return;
      std::vector<Vector<double>> c;
      FullMatrix<double>          J;
      face_rotation_loads(face, c, J);
      rigid_modes.hold(c, J);
    }



    template <int dim>
    std::vector<double>
    Body<dim>::held_moment(const Vector<double> &f) const
    {
      return rigid_modes.held_moment(f);
    }



    template <int dim>
    void
    Body<dim>::correct_for_held_modes(
      const std::vector<PointOperator<dim>> &operators,
      const std::vector<Tensor<1, dim>>     &directions,
      FullMatrix<double>                    &F) const
    {
      const auto        &held_modes   = rigid_modes.held_modes();
      const auto        &held_loads   = rigid_modes.held_loads();
      const auto        &held_inverse = rigid_modes.held_inverse();
      const unsigned int r            = held_modes.size();
      const unsigned int n            = operators.size();
      if (r == 0 || n == 0)
        return;
      AssertDimension(held_response.size(), r);
      Eigen::MatrixXd A(r, n), B(n, r), Gamma(r, r), S_inv(r, r);
      for (unsigned int k = 0; k < r; ++k)
        {
          for (unsigned int j = 0; j < n; ++j)
            {
              A(k, j) =
                directions[j] * operators[j].displacement(held_modes[k]);
              B(j, k) =
                directions[j] * operators[j].displacement(held_response[k]);
            }
          for (unsigned int l = 0; l < r; ++l)
            {
              Gamma(k, l) = held_loads[k] * held_response[l];
              S_inv(k, l) = held_inverse(k, l);
            }
        }
      const Eigen::MatrixXd M  = S_inv * A;
      const Eigen::MatrixXd BM = B * M;
      const Eigen::MatrixXd correction =
        M.transpose() * Gamma * M - BM - BM.transpose();
      for (unsigned int i = 0; i < n; ++i)
        for (unsigned int j = 0; j < n; ++j)
          F(i, j) += correction(i, j);
    }



    template <int dim>
    const std::vector<std::string> &
    Body<dim>::held_rigid_mode_names() const
    {
      return rigid_modes.held_mode_names();
    }



    template const std::vector<Vector<double>> &
    Body<2>::free_rigid_modes() const;
    template const std::vector<Vector<double>> &
    Body<3>::free_rigid_modes() const;
    template const std::vector<std::string> &
    Body<2>::free_rigid_mode_names() const;
    template const std::vector<std::string> &
    Body<3>::free_rigid_mode_names() const;
    template bool
    Body<2>::free_translation(const unsigned int c) const;
    template bool
    Body<3>::free_translation(const unsigned int c) const;
    template void
    Body<2>::find_free_rigid_modes();
    template void
    Body<3>::find_free_rigid_modes();
    template std::vector<double>
    Body<2>::pin_preference() const;
    template std::vector<double>
    Body<3>::pin_preference() const;
    template void
    Body<2>::face_rotation_loads(const types::boundary_id     face,
                                 std::vector<Vector<double>> &c,
                                 FullMatrix<double>          &J) const;
    template void
    Body<3>::face_rotation_loads(const types::boundary_id     face,
                                 std::vector<Vector<double>> &c,
                                 FullMatrix<double>          &J) const;
    template void
    Body<2>::hold_rotations();
    template void
    Body<3>::hold_rotations();
    template std::vector<double>
    Body<2>::held_moment(const Vector<double> &f) const;
    template std::vector<double>
    Body<3>::held_moment(const Vector<double> &f) const;
    template void
    Body<2>::correct_for_held_modes(
      const std::vector<PointOperator<2>> &operators,
      const std::vector<Tensor<1, 2>>     &directions,
      FullMatrix<double>                  &F) const;
    template void
    Body<3>::correct_for_held_modes(
      const std::vector<PointOperator<3>> &operators,
      const std::vector<Tensor<1, 3>>     &directions,
      FullMatrix<double>                  &F) const;
    template const std::vector<std::string> &
    Body<2>::held_rigid_mode_names() const;
    template const std::vector<std::string> &
    Body<3>::held_rigid_mode_names() const;
  } // namespace discretization
} // namespace igabde
