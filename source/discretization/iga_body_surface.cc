// The surfaces of an IgaBody: its candidate contact points with their
// tributary areas, face points and closest points, on the reference
// configuration or on a moved one (Body::move_surfaces()). The space, the
// assembly and the point location are in iga_body.cc.

#include <igabde/base/files.h>
#include <igabde/base/utilities.h>
#include <igabde/linear_algebra/dense_lu.h>

#include <igabde/nurbs/geometry_builders.h>
#include <igabde/nurbs/multi_patch.h>
#include <igabde/nurbs/parametric_mesh.h>

#include <igabde/discretization/iga_body.h>

#include <igabde/elasticity/assembly.h>
#include <igabde/elasticity/finite_output.h>
#include <igabde/elasticity/finite_strain.h>
#include <igabde/elasticity/stress_measures.h>

#include <deal.II/base/data_out_base.h>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <tuple>

namespace igabde
{
  namespace discretization
  {
    namespace
    {
      /// The patch's parametric point at face coordinates @p eta of its
      /// local face @p face (the face's direction at its end, the others
      /// in order), the patch's breaks @p breaks.
      template <int dim>
      Point<dim>
      point_on_face(const std::array<std::vector<double>, dim> &breaks,
                    const unsigned int                          face,
                    const Point<dim - 1>                       &eta)
      {
        const unsigned int d = face / 2;
        Point<dim>         xi;
        for (unsigned int e = 0, k = 0; e < dim; ++e)
          xi[e] =
            (e == d ? (face % 2 == 0 ? breaks[d].front() : breaks[d].back()) :
                      eta[k++]);
        return xi;
      }
    } // namespace



    template <int dim>
    std::vector<SurfacePoint<dim>>
    IgaBody<dim>::surface_points(const types::boundary_id body_face,
                                 const PairPlacement      placement) const
    {
      const auto [space, face]    = patch_face(body_face);
      const auto        &geometry = surface_geometry(*space);
      const unsigned int patch    = patch_of_face<dim>(body_face);
      const unsigned int d        = face / 2;
      const double fixed = (face % 2 == 0 ? geometry.knot_vector(d).front() :
                                            geometry.knot_vector(d).back());

      // Face quadrature: needed for the right-hand side int R_A dGamma and,
      // with the Gauss placement, as the points themselves.
      const unsigned int      p = max_degree();
      std::vector<Point<dim>> qpoints_par; // parametric
      std::vector<double>     qweights;    // dGamma weights
      const auto              face_cps = geometry.face_control_points(face);
      std::map<unsigned int, unsigned int> local_of;
      for (unsigned int k = 0; k < face_cps.size(); ++k)
        local_of[face_cps[k]] = k;
      Eigen::VectorXd integrals = Eigen::VectorXd::Zero(face_cps.size());

      auto integrate = [&](const unsigned int       n_1d,
                           std::vector<Point<dim>> *points_out,
                           std::vector<double>     *weights_out) {
        nurbs::NurbsValues<dim> values(geometry,
                                       QGauss<dim - 1>(n_1d),
                                       update_values | update_JxW_values);
        for (const auto &cell : space->mesh.active_cell_iterators())
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary() &&
                cell->face(f)->boundary_id() == face)
              {
                values.reinit(cell, face);
                for (unsigned int q = 0; q < values.n_quadrature_points(); ++q)
                  {
                    const double dA = values.JxW(q);
                    if (points_out != nullptr)
                      {
                        points_out->push_back(values.parametric_point(q));
                        weights_out->push_back(dA);
                      }
                    else
                      for (unsigned int l = 0; l < values.n_basis(); ++l)
                        {
                          const auto it =
                            local_of.find(values.control_points()[l]);
                          if (it != local_of.end())
                            integrals[it->second] +=
                              values.shape_value(l, q) * dA;
                        }
                  }
              }
      };

      // The points, in the face's lexicographic order.
      std::vector<Point<dim>> xis;
      if (placement == PairPlacement::gauss)
        integrate(p + 1, &xis, &qweights);
      else
        {
          std::array<std::vector<double>, dim> coords;
          for (unsigned int e = 0; e < dim; ++e)
            if (e == d)
              coords[e] = {fixed};
            else if (placement == PairPlacement::greville)
              coords[e] = geometry.knot_vector(e).greville_abscissae();
            else
              coords[e] = space->breaks[e];
          xis = nurbs::tensor_product_points<dim>(coords);
        }

      std::vector<SurfacePoint<dim>> result(xis.size());
      for (unsigned int i = 0; i < xis.size(); ++i)
        {
          result[i].parametric = xis[i];
          result[i].location   = geometry.value(xis[i]);
          result[i].normal     = face_measure_and_normal(face,
                                                     geometry.jacobian(xis[i]),
                                                     space->orientation)
                               .second;
          result[i].op = parametric_point_operator(xis[i], patch);
        }

      if (placement == PairPlacement::gauss)
        {
          for (unsigned int i = 0; i < xis.size(); ++i)
            result[i].tributary_area = qweights[i];
          return result;
        }

      integrate(n_quadrature_points_1d() + 1, nullptr, nullptr);
      Eigen::VectorXd areas;
      if (placement == PairPlacement::greville)
        areas = greville_tributary_areas(*space, face, face_cps, integrals);
      else
        {
          Eigen::MatrixXd M =
            Eigen::MatrixXd::Zero(face_cps.size(), xis.size());
          std::vector<unsigned int> indices;
          std::vector<double>       R;
          for (unsigned int i = 0; i < xis.size(); ++i)
            {
              geometry.basis(xis[i], indices, R);
              for (unsigned int k = 0; k < R.size(); ++k)
                {
                  const auto it = local_of.find(indices[k]);
                  if (it != local_of.end())
                    M(it->second, i) += R[k];
                }
            }
          areas = M.completeOrthogonalDecomposition().solve(integrals);
        }
      for (unsigned int i = 0; i < xis.size(); ++i)
        result[i].tributary_area = areas[i];
      return result;
    }



    template <int dim>
    Eigen::VectorXd
    IgaBody<dim>::greville_tributary_areas(
      const PatchSpace                &space,
      const unsigned int               face,
      const std::vector<unsigned int> &face_cps,
      const Eigen::VectorXd           &integrals) const
    {
      const auto &geometry = surface_geometry(space);
      // sum_i R_A(xi_i) A_i = int R_A dGamma over the face's control points
      // A and Greville points xi_i, both tensor grids of the face's
      // directions. With R_A = w_A N_A / W, N_A = prod_e N_e,a_e and W the
      // weight function, the matrix is D_w (N_1 x N_2) D_W^-1 (x the
      // Kronecker product, N_e(a, i) = N_e,a(g_e,i) the 1D collocation
      // matrices): A = D_W (N_1^-1 x N_2^-1) D_w^-1 b, two sweeps of 1D
      // solves instead of one dense LU of the whole face (20 000 pairs:
      // 5e12 flops and 3 GB).
      const unsigned int            d = face / 2;
      std::vector<unsigned int>     directions;
      std::array<unsigned int, dim> n;
      std::vector<Eigen::MatrixXd>  N;
      std::vector<double>           values;
      for (unsigned int e = 0; e < dim; ++e)
        {
          n[e] = geometry.n_control_points(e);
          if (e == d)
            continue;
          const nurbs::KnotVector &kv = geometry.knot_vector(e);
          const auto               g  = kv.greville_abscissae();
          Eigen::MatrixXd          Ne = Eigen::MatrixXd::Zero(n[e], n[e]);
          for (unsigned int i = 0; i < g.size(); ++i)
            {
              const unsigned int span = kv.find_span(g[i]);
              kv.basis_functions(g[i], span, values);
              for (unsigned int j = 0; j < values.size(); ++j)
                Ne(span - kv.degree() + j, i) = values[j];
            }
          directions.push_back(e);
          N.push_back(std::move(Ne));
        }

      // The face's tensor grid, lowest direction fastest (the order of
      // the Greville points); position of each face control point in it.
      const auto grid_index = [&](const unsigned int control_point) {
        unsigned int rest = control_point, index = 0, stride = 1;
        for (unsigned int e = 0; e < dim; ++e)
          {
            const unsigned int a = rest % n[e];
            rest /= n[e];
            if (e != d)
              {
                index += stride * a;
                stride *= n[e];
              }
          }
        return index;
      };
      const unsigned int size = face_cps.size();
      Eigen::VectorXd    y(size), weights(size);
      for (unsigned int k = 0; k < size; ++k)
        {
          const unsigned int g = grid_index(face_cps[k]);
          weights[g]           = geometry.weight(face_cps[k]);
          y[g]                 = integrals[k] / weights[g];
        }

      // y := (N_1 x N_2)^-1 y and W(xi) = (N_1 x N_2)^T w, one direction
      // at a time; the lines of direction k have stride prod of the
      // earlier face directions.
      unsigned int stride = 1;
      for (unsigned int k = 0; k < directions.size(); ++k)
        {
          const unsigned int            m = n[directions[k]];
          const linear_algebra::DenseLU lu(N[k]);
          AssertThrow(lu.rcond() > 1e-12,
                      ExcMessage("Body '" + this->description().name +
                                 "': the Greville collocation matrix of face " +
                                 std::to_string(face) +
                                 " is singular; this should not happen."));
          Eigen::VectorXd line(m), w_line(m);
          for (unsigned int start = 0; start < size; ++start)
            if ((start / stride) % m == 0)
              {
                for (unsigned int a = 0; a < m; ++a)
                  {
                    line[a]   = y[start + a * stride];
                    w_line[a] = weights[start + a * stride];
                  }
                AssertThrow(lu.solve_in_place(line),
                            ExcMessage("LAPACK dgetrs failed"));
                w_line = N[k].transpose() * w_line;
                for (unsigned int a = 0; a < m; ++a)
                  {
                    y[start + a * stride]       = line[a];
                    weights[start + a * stride] = w_line[a];
                  }
              }
          stride *= m;
        }
      // weights now holds W at the Greville points.
      return weights.cwiseProduct(y);
    }



    template <int dim>
    std::vector<SurfacePoint<dim>>
    IgaBody<dim>::surface_points(const types::boundary_id face) const
    {
      return surface_points(face, default_placement);
    }



    template <int dim>
    FaceGrid<dim>
    IgaBody<dim>::face_grid(const types::boundary_id body_face) const
    {
      const auto [space, face] = patch_face(body_face);
      FaceGrid<dim> grid;
      for (unsigned int e = 0, k = 0; e < dim; ++e)
        if (e != face / 2)
          grid.breaks[k++] = space->breaks[e];
      grid.degree = max_degree();
      return grid;
    }



    template <int dim>
    FacePoint<dim>
    IgaBody<dim>::face_point(const types::boundary_id body_face,
                             const Point<dim - 1>    &eta) const
    {
      const auto [space, face] = patch_face(body_face);
      const unsigned int d     = face / 2;
      const Point<dim>   xi    = point_on_face<dim>(space->breaks, face, eta);
      // One basis evaluation gives the point, its Jacobian and its
      // operator (the moved geometry has the reference one's knots and
      // weights, so the same basis functions): this runs at every step of
      // every closest-point projection.
      const auto &geometry = surface_geometry(*space);
      thread_local std::vector<unsigned int>   indices;
      thread_local std::vector<Tensor<1, dim>> dR;
      FacePoint<dim>                           result;
      geometry.basis(xi, indices, result.op.weights, &dR);
      Tensor<2, dim> J;
      result.gradients.resize(indices.size());
      for (unsigned int l = 0; l < indices.size(); ++l)
        {
          const Point<dim> &x = geometry.control_point(indices[l]);
          result.location += result.op.weights[l] * x;
          J += outer_product(static_cast<const Tensor<1, dim> &>(x), dR[l]);
          for (unsigned int e = 0, k = 0; e < dim; ++e)
            if (e != d)
              result.gradients[l][k++] = dR[l][e];
        }
      std::tie(result.measure, result.normal) =
        face_measure_and_normal(face, J, space->orientation);
      for (unsigned int e = 0, k = 0; e < dim; ++e)
        if (e != d)
          {
            for (unsigned int c = 0; c < dim; ++c)
              result.tangents[k][c] = J[c][e];
            ++k;
          }
      number_operator(indices, patch_of_face<dim>(body_face), result.op);
      return result;
    }



    template <int dim>
    FaceSecondDerivatives<dim>
    IgaBody<dim>::face_second_derivatives(const types::boundary_id body_face,
                                          const Point<dim - 1>    &eta) const
    {
      const auto [space, face] = patch_face(body_face);
      // Face coordinate k is the patch's direction k, or k + 1 past the
      // face's.
      std::array<unsigned int, dim - 1> direction;
      for (unsigned int k = 0; k + 1 < dim; ++k)
        direction[k] = k < face / 2 ? k : k + 1;
      const Point<dim>     xi = point_on_face<dim>(space->breaks, face, eta);
      const Tensor<3, dim> x2 = surface_geometry(*space).second_derivatives(xi);
      FaceSecondDerivatives<dim> result;
      for (unsigned int a = 0; a + 1 < dim; ++a)
        for (unsigned int b = 0; b + 1 < dim; ++b)
          for (unsigned int c = 0; c < dim; ++c)
            result[a][b][c] = x2[c][direction[a]][direction[b]];
      return result;
    }



    template <int dim>
    SurfacePoint<dim>
    IgaBody<dim>::closest_surface_point(const types::boundary_id face,
                                        const Point<dim>        &location,
                                        const SurfacePoint<dim> &nearest) const
    {
      // The nearest surface point (a pair point of this face) starts the
      // search among its spans.
      const auto [space, local] = patch_face(face);
      const auto      &geometry = surface_geometry(*space);
      const Point<dim> xi =
        geometry.closest_point_on_face(local, location, &nearest.parametric);
      SurfacePoint<dim> point;
      point.parametric = xi;
      point.location   = geometry.value(xi);
      point.normal     = geometry.outward_normal(local, xi);
      point.op = parametric_point_operator(xi, patch_of_face<dim>(face));
      return point;
    }



    template <int dim>
    void
    IgaBody<dim>::move_surface_geometry(const Vector<double> *u) const
    {
      moved_geometry.clear();
      if (u == nullptr)
        return;
      for (const PatchSpace &space : spaces)
        {
          const nurbs::NurbsPatch<dim>      &patch = space.geometry;
          std::array<nurbs::KnotVector, dim> knots;
          for (unsigned int d = 0; d < dim; ++d)
            knots[d] = patch.knot_vector(d);
          std::vector<Point<dim>> points(patch.n_control_points());
          std::vector<double>     weights(patch.n_control_points());
          for (unsigned int a = 0; a < points.size(); ++a)
            {
              points[a]  = patch.control_point(a);
              weights[a] = patch.weight(a);
              for (unsigned int c = 0; c < dim; ++c)
                points[a][c] += (*u)[dim * space.numbers[a] + c];
            }
          moved_geometry.emplace_back(knots, points, weights);
        }
    }



    template <int dim>
    const nurbs::NurbsPatch<dim> &
    IgaBody<dim>::surface_geometry(const PatchSpace &space) const
    {
      // Another thread than the one that moved them sees the reference.
      if (!this->surfaces_moved() || moved_geometry.empty())
        return space.geometry;
      return moved_geometry[&space - spaces.data()];
    }



    template std::vector<SurfacePoint<2>>
    IgaBody<2>::surface_points(const types::boundary_id,
                               const PairPlacement) const;
    template std::vector<SurfacePoint<3>>
    IgaBody<3>::surface_points(const types::boundary_id,
                               const PairPlacement) const;
    template Eigen::VectorXd
    IgaBody<2>::greville_tributary_areas(const PatchSpace &,
                                         const unsigned int,
                                         const std::vector<unsigned int> &,
                                         const Eigen::VectorXd &) const;
    template Eigen::VectorXd
    IgaBody<3>::greville_tributary_areas(const PatchSpace &,
                                         const unsigned int,
                                         const std::vector<unsigned int> &,
                                         const Eigen::VectorXd &) const;
    template std::vector<SurfacePoint<2>>
    IgaBody<2>::surface_points(const types::boundary_id) const;
    template std::vector<SurfacePoint<3>>
    IgaBody<3>::surface_points(const types::boundary_id) const;
    template FaceGrid<2>
    IgaBody<2>::face_grid(const types::boundary_id) const;
    template FaceGrid<3>
    IgaBody<3>::face_grid(const types::boundary_id) const;
    template FacePoint<2>
    IgaBody<2>::face_point(const types::boundary_id, const Point<1> &) const;
    template FacePoint<3>
    IgaBody<3>::face_point(const types::boundary_id, const Point<2> &) const;
    template FaceSecondDerivatives<2>
    IgaBody<2>::face_second_derivatives(const types::boundary_id,
                                        const Point<1> &) const;
    template FaceSecondDerivatives<3>
    IgaBody<3>::face_second_derivatives(const types::boundary_id,
                                        const Point<2> &) const;
    template SurfacePoint<2>
    IgaBody<2>::closest_surface_point(const types::boundary_id,
                                      const Point<2> &,
                                      const SurfacePoint<2> &) const;
    template SurfacePoint<3>
    IgaBody<3>::closest_surface_point(const types::boundary_id,
                                      const Point<3> &,
                                      const SurfacePoint<3> &) const;
    template void
    IgaBody<2>::move_surface_geometry(const Vector<double> *) const;
    template void
    IgaBody<3>::move_surface_geometry(const Vector<double> *) const;
    template const nurbs::NurbsPatch<2> &
    IgaBody<2>::surface_geometry(const PatchSpace &) const;
    template const nurbs::NurbsPatch<3> &
    IgaBody<3>::surface_geometry(const PatchSpace &) const;
  } // namespace discretization
} // namespace igabde
