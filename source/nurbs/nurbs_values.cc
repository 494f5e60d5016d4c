#include <igabde/nurbs/nurbs_values.h>
#include <igabde/nurbs/parametric_mesh.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/polynomials_bernstein.h>

#include <cmath>

namespace igabde
{
  namespace nurbs
  {
    template <int dim>
    NurbsValues<dim>::NurbsValues(const NurbsPatch<dim> &patch,
                                  const Quadrature<dim> &quadrature,
                                  const UpdateFlags      flags)
      : patch(&patch)
      , flags(flags)
      , face_rule(false)
    {
      initialize({quadrature.get_points()}, quadrature.get_weights());
    }



    template <int dim>
    NurbsValues<dim>::NurbsValues(const NurbsPatch<dim>     &patch,
                                  const Quadrature<dim - 1> &face_quadrature,
                                  const UpdateFlags          flags)
      : patch(&patch)
      , flags(flags)
      , face_rule(true)
    {
      // One point set per cell face: the face coordinate fixed at 0 or 1.
      std::vector<std::vector<Point<dim>>> sets(2 * dim);
      for (unsigned int face = 0; face < 2 * dim; ++face)
        {
          const unsigned int d = face / 2;
          sets[face].resize(face_quadrature.size());
          for (unsigned int i = 0; i < face_quadrature.size(); ++i)
            {
              unsigned int k = 0;
              for (unsigned int e = 0; e < dim; ++e)
                if (e == d)
                  sets[face][i][e] = (face % 2 == 0 ? 0. : 1.);
                else
                  sets[face][i][e] = face_quadrature.point(i)[k++];
            }
        }
      initialize(sets, face_quadrature.get_weights());
    }



    template <int dim>
    void
    NurbsValues<dim>::initialize(
      const std::vector<std::vector<Point<dim>>> &sets,
      const std::vector<double>                  &weights)
    {
      auto d_data = std::make_shared<Data>();
      n_local     = 1;
      for (unsigned int d = 0; d < dim; ++d)
        {
          const KnotVector &kv  = patch->knot_vector(d);
          d_data->extraction[d] = kv.bezier_extraction_operators();
          d_data->breaks[d]     = kv.breakpoints();
          d_data->span_knot_index[d].resize(kv.n_spans());
          for (unsigned int e = 0; e < kv.n_spans(); ++e)
            d_data->span_knot_index[d][e] = kv.span_knot_index(e);
          n_1d[d] = kv.degree() + 1;
          n_local *= n_1d[d];
        }
      d_data->reference = sets;
      d_data->weights.assign(sets.size(), weights);
      d_data->B.resize(sets.size());
      d_data->dB.resize(sets.size());
      std::array<std::vector<Polynomials::Polynomial<double>>, dim> bernstein;
      for (unsigned int d = 0; d < dim; ++d)
        bernstein[d] = generate_complete_bernstein_basis<double>(n_1d[d] - 1);
      std::vector<double> bv(2);
      for (unsigned int s = 0; s < sets.size(); ++s)
        {
          d_data->B[s].resize(sets[s].size());
          d_data->dB[s].resize(sets[s].size());
          for (unsigned int q = 0; q < sets[s].size(); ++q)
            for (unsigned int d = 0; d < dim; ++d)
              {
                d_data->B[s][q][d].resize(n_1d[d]);
                d_data->dB[s][q][d].resize(n_1d[d]);
                for (unsigned int j = 0; j < n_1d[d]; ++j)
                  {
                    bernstein[d][j].value(sets[s][q][d], bv);
                    d_data->B[s][q][d][j]  = bv[0];
                    d_data->dB[s][q][d][j] = bv[1];
                  }
              }
        }
      data        = d_data;
      orientation = patch->orientation();

      n_q = sets[0].size();
      local_control_points.resize(n_local);
      values.resize(n_q * n_local);
      parametric_gradients.resize(n_q * n_local);
      if (flags & update_gradients)
        gradients.resize(n_q * n_local);
      points.resize(n_q);
      parametric_points.resize(n_q);
      jacobians.resize(n_q);
      jxw.resize(n_q);
      normals.resize(n_q);
      is_regular.resize(n_q);
      for (unsigned int d = 0; d < dim; ++d)
        {
          N[d].resize(n_1d[d]);
          dN[d].resize(n_1d[d]);
        }
    }



    template <int dim>
    void
    NurbsValues<dim>::check_orientation(const std::string &owner)
    {
      orientation_owner = owner;
    }



    template <int dim>
    void
    NurbsValues<dim>::reinit(const cell_iterator &cell)
    {
      Assert(!face_rule, ExcMessage("A face rule needs reinit(cell, face)."));
      reinit(span_of_point<dim>(data->breaks, cell->center()));
    }



    template <int dim>
    void
    NurbsValues<dim>::reinit(const cell_iterator &cell, const unsigned int face)
    {
      Assert(face_rule, ExcMessage("A cell rule needs reinit(cell)."));
      reinit(span_of_point<dim>(data->breaks, cell->center()), face);
    }



    template <int dim>
    void
    NurbsValues<dim>::get_dof_indices(
      std::vector<types::global_dof_index> &dofs) const
    {
      dofs.resize(dim * n_local);
      for (unsigned int l = 0; l < n_local; ++l)
        for (unsigned int c = 0; c < dim; ++c)
          dofs[dim * l + c] = dim * (numbering != nullptr ?
                                       (*numbering)[local_control_points[l]] :
                                       local_control_points[l]) +
                              c;
    }



    template <int dim>
    void
    NurbsValues<dim>::number_unknowns_by(
      const std::vector<unsigned int> &control_point_numbers)
    {
      AssertDimension(control_point_numbers.size(), patch->n_control_points());
      numbering = &control_point_numbers;
    }



    template <int dim>
    void
    NurbsValues<dim>::reinit(const std::array<unsigned int, dim> &span,
                             const unsigned int                   face)
    {
      const Data        &D   = *data;
      const unsigned int set = (face_rule ? face : 0);
      AssertIndexRange(set, D.reference.size());
      current_span = span;

      Tensor<1, dim> h;
      for (unsigned int d = 0; d < dim; ++d)
        h[d] = D.breaks[d][span[d] + 1] - D.breaks[d][span[d]];
      // Measure of the reference cell (or face) in parametric coordinates.
      double hprod = 1.;
      for (unsigned int d = 0; d < dim; ++d)
        if (!face_rule || d != face / 2)
          hprod *= h[d];

      for (unsigned int l = 0; l < n_local; ++l)
        {
          unsigned int                  rest = l;
          std::array<unsigned int, dim> global;
          for (unsigned int d = 0; d < dim; ++d)
            {
              global[d] =
                D.span_knot_index[d][span[d]] - (n_1d[d] - 1) + rest % n_1d[d];
              rest /= n_1d[d];
            }
          local_control_points[l] = patch->control_point_index(global);
        }

      const bool with_gradients = (flags & update_gradients);
      for (unsigned int q = 0; q < n_q; ++q)
        {
          // 1D B-splines on the span: N = C^e B (Bernstein on [0, 1]).
          for (unsigned int d = 0; d < dim; ++d)
            {
              const unsigned int         n_d = n_1d[d];
              const FullMatrix<double>  &C   = D.extraction[d][span[d]];
              const std::vector<double> &B   = D.B[set][q][d];
              const std::vector<double> &dB  = D.dB[set][q][d];
              for (unsigned int a = 0; a < n_d; ++a)
                {
                  double v = 0., g = 0.;
                  for (unsigned int j = 0; j < n_d; ++j)
                    {
                      v += C(a, j) * B[j];
                      g += C(a, j) * dB[j] / h[d];
                    }
                  N[d][a]  = v;
                  dN[d][a] = g;
                }
              parametric_points[q][d] =
                D.breaks[d][span[d]] + h[d] * D.reference[set][q][d];
            }

          // Tensor product, then the NURBS quotient rule.
          double         *R  = &values[q * n_local];
          Tensor<1, dim> *dR = &parametric_gradients[q * n_local];
          double          W  = 0.;
          Tensor<1, dim>  dW;
          for (unsigned int l = 0; l < n_local; ++l)
            {
              std::array<unsigned int, dim> a;
              unsigned int                  rest = l;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  a[d] = rest % n_1d[d];
                  rest /= n_1d[d];
                }
              const double w = patch->weight(local_control_points[l]);
              double       v = w;
              for (unsigned int d = 0; d < dim; ++d)
                v *= N[d][a[d]];
              Tensor<1, dim> g;
              for (unsigned int b = 0; b < dim; ++b)
                {
                  double gb = w;
                  for (unsigned int d = 0; d < dim; ++d)
                    gb *= (d == b ? dN[d][a[d]] : N[d][a[d]]);
                  g[b] = gb;
                }
              R[l]  = v;
              dR[l] = g;
              W += v;
              dW += g;
            }
          Point<dim>     x;
          Tensor<2, dim> J;
          for (unsigned int l = 0; l < n_local; ++l)
            {
              dR[l] = (dR[l] * W - R[l] * dW) / (W * W);
              R[l] /= W;
              const Point<dim> &P =
                patch->control_point(local_control_points[l]);
              x += R[l] * P;
              for (unsigned int i = 0; i < dim; ++i)
                for (unsigned int j = 0; j < dim; ++j)
                  J[i][j] += P[i] * dR[l][j];
            }
          points[q]    = x;
          jacobians[q] = J;

          const double detJ = determinant(J);
          if (!face_rule)
            {
              AssertThrow(orientation_owner.empty() || detJ * orientation > 0.,
                          ExcMessage(orientation_owner +
                                     ": the NURBS map folds or degenerates "
                                     "inside a knot span (det J = " +
                                     std::to_string(detJ) +
                                     "); check the control net."));
              jxw[q] = std::abs(detJ) * hprod * D.weights[set][q];
            }
          else
            {
              const unsigned int   d    = face / 2;
              const double         side = (face % 2 == 0 ? -1. : 1.);
              const Tensor<1, dim> c    = cofactor_column(J, d);
              const double         norm = c.norm();
              normals[q]                = Tensor<1, dim>();
              if (norm > 0.)
                normals[q] = (side * orientation / norm) * c;
              jxw[q] = norm * hprod * D.weights[set][q];
            }

          if (with_gradients)
            {
              is_regular[q] = std::abs(detJ) > 1e-10 * std::pow(J.norm(), dim);
              Tensor<1, dim> *grad = &gradients[q * n_local];
              if (is_regular[q])
                {
                  const Tensor<2, dim> JinvT = transpose(invert(J));
                  for (unsigned int l = 0; l < n_local; ++l)
                    grad[l] = JinvT * dR[l];
                }
              else
                for (unsigned int l = 0; l < n_local; ++l)
                  grad[l] = Tensor<1, dim>();
            }
        }
    }



    template class NurbsValues<2>;
    template class NurbsValues<3>;
  } // namespace nurbs
} // namespace igabde
