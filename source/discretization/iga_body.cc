#include <igabde/base/utilities.h>

#include <igabde/nurbs/geometry_builders.h>
#include <igabde/nurbs/parametric_mesh.h>

#include <igabde/discretization/iga_body.h>

#include <deal.II/base/data_out_base.h>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/polynomials_bernstein.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/work_stream.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

namespace igabde
{
  namespace discretization
  {
    namespace
    {

      /// Symmetric gradient of the vector function R e_c.
      template <int dim>
      SymmetricTensor<2, dim>
      basis_strain(const Tensor<1, dim> &grad, const unsigned int c)
      {
        SymmetricTensor<2, dim> e;
        for (unsigned int j = 0; j < dim; ++j)
          e[c][j] += (c == j ? grad[j] : 0.5 * grad[j]);
        return e;
      }

      /// Tensor index of local function l for degrees p.
      template <int dim>
      std::array<unsigned int, dim>
      local_index(unsigned int l, const std::array<unsigned int, dim> &n)
      {
        std::array<unsigned int, dim> a;
        for (unsigned int d = 0; d < dim; ++d)
          {
            a[d] = l % n[d];
            l /= n[d];
          }
        return a;
      }
    } // namespace



    template <int dim>
    IgaBody<dim>::IgaBody(const BodyDescription<dim>   &description,
                          const DiscretizationSettings &settings)
      : Body<dim>(description, settings)
      , geometry(description.geometry)
    {
      AssertThrow(geometry.n_control_points() > 0,
                  ExcMessage("Body '" + description.name +
                             "': the description has no NURBS geometry; "
                             "build one with the nurbs/geometry_builders."));
      AssertThrow(settings.degree >= 1,
                  ExcMessage("Body '" + description.name +
                             "': the NURBS degree must be at least 1."));
      // An exact geometry cannot be lowered (a circle needs rational
      // degree 2): running at the geometry's degree while reporting the
      // requested one would be a silent wrong answer.
      for (unsigned int d = 0; d < dim; ++d)
        AssertThrow(
          geometry.degree(d) <= settings.degree,
          base::ExcInput(
            "Discretization/Degree = " + std::to_string(settings.degree) +
            " is below the degree " + std::to_string(geometry.degree(d)) +
            " of " + description.name +
            "'s exact geometry in parametric "
            "direction " +
            std::to_string(d) +
            "; use Degree >= " + std::to_string(geometry.degree(d)) +
            " with NURBS, or Discretization/Type = lagrange for an "
            "FE_Q approximation of this geometry."));
      nurbs::elevate_to_degree(geometry, settings.degree);
      for (unsigned int r = 0; r < settings.refinements; ++r)
        geometry.refine_uniformly(1);

      nurbs::make_parametric_triangulation(geometry, parametric_mesh);

      for (unsigned int d = 0; d < dim; ++d)
        {
          const nurbs::KnotVector &kv = geometry.knot_vector(d);
          extraction[d]               = kv.bezier_extraction_operators();
          breaks[d]                   = kv.breakpoints();
          span_knot_index[d].resize(kv.n_spans());
          for (unsigned int e = 0; e < kv.n_spans(); ++e)
            span_knot_index[d][e] = kv.span_knot_index(e);
          bernstein[d] = generate_complete_bernstein_basis<double>(kv.degree());
        }
      orientation = geometry.orientation();

      Point<dim> lo = geometry.control_point(0), hi = lo;
      for (unsigned int a = 0; a < geometry.n_control_points(); ++a)
        for (unsigned int d = 0; d < dim; ++d)
          {
            lo[d] = std::min(lo[d], geometry.control_point(a)[d]);
            hi[d] = std::max(hi[d], geometry.control_point(a)[d]);
          }
      diameter = (hi - lo).norm();

      // Newton starts for the point inversion: breakpoints and span
      // midpoints, cell by cell so that the samples are cheap to evaluate.
      std::array<std::vector<double>, dim> samples;
      unsigned int                         n_samples = 1;
      for (unsigned int d = 0; d < dim; ++d)
        {
          for (unsigned int e = 0; e + 1 < breaks[d].size(); ++e)
            {
              samples[d].push_back(breaks[d][e]);
              samples[d].push_back(0.5 * (breaks[d][e] + breaks[d][e + 1]));
            }
          samples[d].push_back(breaks[d].back());
          n_samples *= samples[d].size();
        }
      sample_parametric.resize(n_samples);
      sample_physical.resize(n_samples);
      for (unsigned int s = 0; s < n_samples; ++s)
        {
          unsigned int rest = s;
          for (unsigned int d = 0; d < dim; ++d)
            {
              sample_parametric[s][d] = samples[d][rest % samples[d].size()];
              rest /= samples[d].size();
            }
          sample_physical[s] = geometry.value(sample_parametric[s]);
        }
    }



    template <int dim>
    std::string
    IgaBody<dim>::discretization_name() const
    {
      return "nurbs";
    }



    template <int dim>
    unsigned int
    IgaBody<dim>::n_elements() const
    {
      return parametric_mesh.n_active_cells();
    }



    template <int dim>
    const nurbs::NurbsPatch<dim> &
    IgaBody<dim>::patch() const
    {
      return geometry;
    }



    template <int dim>
    const Triangulation<dim> &
    IgaBody<dim>::triangulation() const
    {
      return parametric_mesh;
    }



    template <int dim>
    unsigned int
    IgaBody<dim>::max_degree() const
    {
      unsigned int p = 0;
      for (unsigned int d = 0; d < dim; ++d)
        p = std::max(p, geometry.degree(d));
      return p;
    }



    template <int dim>
    unsigned int
    IgaBody<dim>::n_quadrature_points_1d() const
    {
      bool rational = false;
      for (unsigned int a = 1; a < geometry.n_control_points(); ++a)
        rational = rational || (geometry.weight(a) != geometry.weight(0));
      return max_degree() + (rational ? 2 : 1);
    }



    template <int dim>
    Tensor<1, dim>
    IgaBody<dim>::span_lengths(const std::array<unsigned int, dim> &span) const
    {
      Tensor<1, dim> h;
      for (unsigned int d = 0; d < dim; ++d)
        h[d] = breaks[d][span[d] + 1] - breaks[d][span[d]];
      return h;
    }



    template <int dim>
    void
    IgaBody<dim>::evaluate_cell(const std::array<unsigned int, dim> &span,
                                const std::vector<Point<dim>>       &reference,
                                CellEvaluation &result) const
    {
      std::array<unsigned int, dim> n_1d;
      unsigned int                  n_local = 1;
      for (unsigned int d = 0; d < dim; ++d)
        {
          n_1d[d] = geometry.degree(d) + 1;
          n_local *= n_1d[d];
        }
      const Tensor<1, dim> h = span_lengths(span);

      result.control_points.resize(n_local);
      for (unsigned int l = 0; l < n_local; ++l)
        {
          const auto                    a = local_index<dim>(l, n_1d);
          std::array<unsigned int, dim> global;
          for (unsigned int d = 0; d < dim; ++d)
            global[d] = span_knot_index[d][span[d]] - geometry.degree(d) + a[d];
          result.control_points[l] = geometry.control_point_index(global);
        }

      const unsigned int n_q = reference.size();
      result.values.resize(n_q);
      result.parametric_gradients.resize(n_q);
      result.points.resize(n_q);
      result.jacobians.resize(n_q);
      result.parametric_points.resize(n_q);

      std::array<std::vector<double>, dim> N, dN;
      std::vector<double>                  bv(2);
      std::vector<double>                  B, dB;
      for (unsigned int q = 0; q < n_q; ++q)
        {
          // 1D B-splines on the span: N = C^e B (Bernstein on [0, 1]).
          for (unsigned int d = 0; d < dim; ++d)
            {
              const unsigned int        p = geometry.degree(d);
              const FullMatrix<double> &C = extraction[d][span[d]];
              B.resize(p + 1);
              dB.resize(p + 1);
              for (unsigned int j = 0; j <= p; ++j)
                {
                  bernstein[d][j].value(reference[q][d], bv);
                  B[j]  = bv[0];
                  dB[j] = bv[1];
                }
              N[d].assign(p + 1, 0.);
              dN[d].assign(p + 1, 0.);
              for (unsigned int a = 0; a <= p; ++a)
                for (unsigned int j = 0; j <= p; ++j)
                  {
                    N[d][a] += C(a, j) * B[j];
                    dN[d][a] += C(a, j) * dB[j] / h[d];
                  }
              result.parametric_points[q][d] =
                breaks[d][span[d]] + h[d] * reference[q][d];
            }

          // Tensor product, then the NURBS quotient rule.
          auto &R  = result.values[q];
          auto &dR = result.parametric_gradients[q];
          R.resize(n_local);
          dR.resize(n_local);
          double         W = 0.;
          Tensor<1, dim> dW;
          for (unsigned int l = 0; l < n_local; ++l)
            {
              const auto   a = local_index<dim>(l, n_1d);
              const double w = geometry.weight(result.control_points[l]);
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
                geometry.control_point(result.control_points[l]);
              x += R[l] * P;
              for (unsigned int i = 0; i < dim; ++i)
                for (unsigned int j = 0; j < dim; ++j)
                  J[i][j] += P[i] * dR[l][j];
            }
          result.points[q]    = x;
          result.jacobians[q] = J;
        }
    }



    template <int dim>
    void
    IgaBody<dim>::face_rule(const unsigned int       face,
                            const unsigned int       n_points_1d,
                            std::vector<Point<dim>> &points,
                            std::vector<double>     &weights) const
    {
      const QGauss<dim - 1> q(n_points_1d);
      const unsigned int    d = face / 2;
      points.resize(q.size());
      weights.resize(q.size());
      for (unsigned int i = 0; i < q.size(); ++i)
        {
          unsigned int k = 0;
          for (unsigned int e = 0; e < dim; ++e)
            if (e == d)
              points[i][e] = (face % 2 == 0 ? 0. : 1.);
            else
              points[i][e] = q.point(i)[k++];
          weights[i] = q.weight(i);
        }
    }



    template <int dim>
    std::pair<double, Tensor<1, dim>>
    IgaBody<dim>::face_measure_and_normal(const unsigned int    face,
                                          const Tensor<2, dim> &J) const
    {
      const unsigned int   d    = face / 2;
      const double         side = (face % 2 == 0 ? -1. : 1.);
      const Tensor<1, dim> c    = nurbs::cofactor_column(J, d);
      const double         norm = c.norm();
      Tensor<1, dim>       n;
      if (norm > 0.)
        n = (side * orientation / norm) * c;
      return {norm, n};
    }



    template <int dim>
    void
    IgaBody<dim>::setup_space()
    {
      const unsigned int n_cp = geometry.n_control_points();
      this->n_unknowns        = dim * n_cp;
      this->dof_locations.resize(this->n_unknowns);
      this->dof_components.resize(this->n_unknowns);
      for (unsigned int a = 0; a < n_cp; ++a)
        for (unsigned int c = 0; c < dim; ++c)
          {
            this->dof_locations[dim * a + c]  = geometry.control_point(a);
            this->dof_components[dim * a + c] = c;
          }

      // Supports: with open knot vectors only the face's control points
      // have a nonzero trace there, and sum R = 1 makes a constant value
      // exact when it is given to all of them.
      const std::string name = this->body_description.name;
      this->constraints.clear();
      this->prescribed_constraints.clear();
      std::map<types::global_dof_index, double> values;
      for (const auto &bc : this->body_description.dirichlet)
        {
          AssertThrow(bc.boundary_id < 2 * dim,
                      ExcMessage("Body '" + name + "': Dirichlet face " +
                                 std::to_string(bc.boundary_id) +
                                 " does not exist; patch faces are 0.." +
                                 std::to_string(2 * dim - 1) + "."));
          for (const unsigned int a :
               geometry.face_control_points(bc.boundary_id))
            for (unsigned int c = 0; c < dim; ++c)
              if (bc.components[c])
                {
                  const types::global_dof_index i  = dim * a + c;
                  const auto                    it = values.find(i);
                  if (it != values.end())
                    AssertThrow(std::abs(it->second - bc.value[c]) <=
                                  1e-12 * std::max(1., std::abs(bc.value[c])),
                                ExcMessage(
                                  "Body '" + name +
                                  "': two supports prescribe different "
                                  "values of component " +
                                  std::to_string(c) +
                                  " where their faces meet (face " +
                                  std::to_string(bc.boundary_id) +
                                  "); make them agree on the common edge."));
                  values[i] = bc.value[c];
                }
        }
      for (const auto &[i, v] : values)
        {
          this->constraints.add_line(i);
          this->prescribed_constraints.add_line(i);
          this->prescribed_constraints.set_inhomogeneity(i, v);
        }
      this->constraints.close();
      this->prescribed_constraints.close();

      DynamicSparsityPattern dsp(this->n_unknowns, this->n_unknowns);
      CellEvaluation         eval;
      for (const auto &cell : parametric_mesh.active_cell_iterators())
        {
          const auto span = nurbs::span_of_point<dim>(breaks, cell->center());
          evaluate_cell(span, {}, eval);
          std::vector<types::global_dof_index> dofs;
          for (const unsigned int a : eval.control_points)
            for (unsigned int c = 0; c < dim; ++c)
              dofs.push_back(dim * a + c);
          std::sort(dofs.begin(), dofs.end());
          for (const auto i : dofs)
            dsp.add_entries(i, dofs.begin(), dofs.end(), true);
        }
      this->sparsity.copy_from(dsp);
    }



    template <int dim>
    void
    IgaBody<dim>::assemble()
    {
      const auto &desc = this->body_description;
      for (const auto &t : desc.tractions)
        AssertThrow(t.boundary_id < 2 * dim,
                    ExcMessage("Body '" + desc.name + "': traction face " +
                               std::to_string(t.boundary_id) +
                               " does not exist; patch faces are 0.." +
                               std::to_string(2 * dim - 1) + "."));

      this->system_matrix.reinit(this->sparsity);
      this->load_rhs.reinit(this->n_unknowns);

      const QGauss<dim>       quadrature(n_quadrature_points_1d());
      const unsigned int      n_face_1d      = n_quadrature_points_1d() + 1;
      SymmetricTensor<4, dim> C              = desc.material.stiffness();
      const Tensor<1, dim>    body_force     = desc.body_force;
      const bool              has_body_force = body_force.norm() > 0.;

      struct Scratch
      {
        CellEvaluation              eval, face_eval;
        std::vector<Tensor<1, dim>> gradients;
      };
      // The stiffness is isotropic (plane strain, plane stress with its
      // reduced lambda, or 3D): read lambda and mu off C and check the form.
      const double lambda = C[0][0][1][1];
      const double mu     = C[0][1][0][1];
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          for (unsigned int k = 0; k < dim; ++k)
            for (unsigned int l = 0; l < dim; ++l)
              Assert(std::abs(C[i][j][k][l] - (lambda * (i == j) * (k == l) +
                                               mu * ((i == k) * (j == l) +
                                                     (i == l) * (j == k)))) <=
                       1e-12 * (std::abs(lambda) + mu),
                     ExcMessage("The IGA assembly assumes an isotropic C."));
      struct Copy
      {
        FullMatrix<double>                   matrix;
        Vector<double>                       rhs;
        std::vector<types::global_dof_index> dofs;
      };

      auto worker =
        [&](const typename Triangulation<dim>::active_cell_iterator &cell,
            Scratch                                                 &scratch,
            Copy                                                    &copy) {
          const auto span = nurbs::span_of_point<dim>(breaks, cell->center());
          const Tensor<1, dim> h     = span_lengths(span);
          double               hprod = 1.;
          for (unsigned int d = 0; d < dim; ++d)
            hprod *= h[d];

          CellEvaluation &ev = scratch.eval;
          evaluate_cell(span, quadrature.get_points(), ev);
          const unsigned int n_local = ev.control_points.size();
          const unsigned int n_dofs  = dim * n_local;
          copy.matrix.reinit(n_dofs, n_dofs);
          copy.rhs.reinit(n_dofs);
          copy.dofs.resize(n_dofs);
          for (unsigned int l = 0; l < n_local; ++l)
            for (unsigned int c = 0; c < dim; ++c)
              copy.dofs[dim * l + c] = dim * ev.control_points[l] + c;

          std::vector<Tensor<1, dim>> &grads = scratch.gradients;
          grads.resize(n_local);
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              const Tensor<2, dim> &J    = ev.jacobians[q];
              const double          detJ = determinant(J);
              AssertThrow(detJ * orientation > 0.,
                          ExcMessage("Body '" + desc.name +
                                     "': the NURBS map folds or degenerates "
                                     "inside a knot span (det J = " +
                                     std::to_string(detJ) +
                                     "); check the control net."));
              const double JxW = std::abs(detJ) * hprod * quadrature.weight(q);
              const Tensor<2, dim> Jinv = invert(J);
              for (unsigned int l = 0; l < n_local; ++l)
                grads[l] = transpose(Jinv) * ev.parametric_gradients[q][l];
              // Isotropic C = lambda I x I + 2 mu I^s with the basis strains
              // sym(g_a x e_c): K(ac, bd) = lambda g_a[c] g_b[d]
              // + mu (delta_cd g_a . g_b + g_a[d] g_b[c]), upper triangle.
              for (unsigned int a = 0; a < n_local; ++a)
                {
                  const Tensor<1, dim> la = (lambda * JxW) * grads[a];
                  const Tensor<1, dim> ma = (mu * JxW) * grads[a];
                  for (unsigned int b = a; b < n_local; ++b)
                    {
                      const Tensor<1, dim> &gb  = grads[b];
                      const double          dot = ma * gb;
                      for (unsigned int c = 0; c < dim; ++c)
                        for (unsigned int d = 0; d < dim; ++d)
                          copy.matrix(dim * a + c, dim * b + d) +=
                            la[c] * gb[d] + ma[d] * gb[c] + (c == d ? dot : 0.);
                    }
                }
              if (has_body_force)
                for (unsigned int l = 0; l < n_local; ++l)
                  for (unsigned int c = 0; c < dim; ++c)
                    copy.rhs[dim * l + c] +=
                      ev.values[q][l] * body_force[c] * JxW;
            }
          // Blocks below the diagonal from their transposes above it.
          for (unsigned int a = 0; a < n_local; ++a)
            for (unsigned int b = 0; b < a; ++b)
              for (unsigned int c = 0; c < dim; ++c)
                for (unsigned int d = 0; d < dim; ++d)
                  copy.matrix(dim * a + c, dim * b + d) =
                    copy.matrix(dim * b + d, dim * a + c);

          // Tractions on the patch faces this span touches.
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary())
              for (const auto &neumann : desc.tractions)
                if (neumann.boundary_id == cell->face(f)->boundary_id())
                  {
                    const unsigned int      face = neumann.boundary_id;
                    std::vector<Point<dim>> points;
                    std::vector<double>     weights;
                    face_rule(face, n_face_1d, points, weights);
                    double hface = 1.;
                    for (unsigned int d = 0; d < dim; ++d)
                      if (d != face / 2)
                        hface *= h[d];
                    CellEvaluation &fe = scratch.face_eval;
                    evaluate_cell(span, points, fe);
                    for (unsigned int q = 0; q < points.size(); ++q)
                      {
                        const auto [ds, n] =
                          face_measure_and_normal(face, fe.jacobians[q]);
                        if (ds == 0.)
                          continue;
                        const Tensor<1, dim> t =
                          neumann.traction(fe.points[q], n);
                        const double dA = ds * hface * weights[q];
                        for (unsigned int l = 0; l < n_local; ++l)
                          for (unsigned int c = 0; c < dim; ++c)
                            copy.rhs[dim * l + c] +=
                              fe.values[q][l] * t[c] * dA;
                      }
                  }
        };

      auto copier = [&](const Copy &copy) {
        this->system_matrix.add(copy.dofs, copy.matrix);
        for (unsigned int i = 0; i < copy.dofs.size(); ++i)
          this->load_rhs[copy.dofs[i]] += copy.rhs[i];
      };

      WorkStream::run(parametric_mesh.begin_active(),
                      parametric_mesh.end(),
                      worker,
                      copier,
                      Scratch(),
                      Copy());

      // Point loads: P_A = R_A(xi_X) P (method.md, sec. 3).
      for (const auto &load : desc.point_loads)
        point_operator(load.location).distribute(load.force, this->load_rhs);
    }



    template <int dim>
    Point<dim>
    IgaBody<dim>::parametric_point(const Point<dim> &location) const
    {
      unsigned int best   = 0;
      double       best_d = std::numeric_limits<double>::max();
      for (unsigned int s = 0; s < sample_physical.size(); ++s)
        {
          const double d = (sample_physical[s] - location).norm_square();
          if (d < best_d)
            {
              best_d = d;
              best   = s;
            }
        }
      double           distance = 0.;
      const Point<dim> xi =
        geometry.closest_parametric_point(location,
                                          &sample_parametric[best],
                                          &distance);
      if (distance > 1e-8 * diameter)
        {
          std::ostringstream s;
          s << "Body '" << this->body_description.name << "': the point ("
            << location << ") is not in the body (distance " << distance
            << " from its closest point (" << geometry.value(xi)
            << ")); point loads and probes must lie in or on the body.";
          AssertThrow(false, ExcMessage(s.str()));
        }
      return xi;
    }



    template <int dim>
    PointOperator<dim>
    IgaBody<dim>::parametric_point_operator(const Point<dim> &xi) const
    {
      std::vector<unsigned int> indices;
      PointOperator<dim>        op;
      geometry.basis(xi, indices, op.weights);
      op.dofs.resize(indices.size());
      for (unsigned int k = 0; k < indices.size(); ++k)
        for (unsigned int c = 0; c < dim; ++c)
          op.dofs[k][c] = dim * indices[k] + c;
      return op;
    }



    template <int dim>
    PointOperator<dim>
    IgaBody<dim>::point_operator(const Point<dim> &location) const
    {
      return parametric_point_operator(parametric_point(location));
    }



    template <int dim>
    Tensor<1, dim>
    IgaBody<dim>::displacement_at_parametric(const Vector<double> &u,
                                             const Point<dim>     &xi) const
    {
      return parametric_point_operator(xi).displacement(u);
    }



    template <int dim>
    std::vector<SurfacePoint<dim>>
    IgaBody<dim>::surface_points(const types::boundary_id face,
                                 const PairPlacement      placement) const
    {
      AssertThrow(face < 2 * dim,
                  ExcMessage("Body '" + this->body_description.name +
                             "': face " + std::to_string(face) +
                             " does not exist; patch faces are 0.." +
                             std::to_string(2 * dim - 1) + "."));
      const unsigned int d = face / 2;
      const double fixed   = (face % 2 == 0 ? geometry.knot_vector(d).front() :
                                              geometry.knot_vector(d).back());

      // Face quadrature: needed for the right-hand side int R_A dGamma and,
      // with the Gauss placement, as the points themselves.
      const unsigned int      p = max_degree();
      std::vector<Point<dim>> qpoints_par; // parametric
      std::vector<double>     qweights;    // dGamma weights
      std::vector<Point<dim>> face_ref;
      std::vector<double>     face_w;
      const auto              face_cps = geometry.face_control_points(face);
      std::map<unsigned int, unsigned int> local_of;
      for (unsigned int k = 0; k < face_cps.size(); ++k)
        local_of[face_cps[k]] = k;
      Eigen::VectorXd integrals = Eigen::VectorXd::Zero(face_cps.size());

      auto integrate = [&](const unsigned int       n_1d,
                           std::vector<Point<dim>> *points_out,
                           std::vector<double>     *weights_out) {
        face_rule(face, n_1d, face_ref, face_w);
        CellEvaluation ev;
        for (const auto &cell : parametric_mesh.active_cell_iterators())
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary() &&
                cell->face(f)->boundary_id() == face)
              {
                const auto span =
                  nurbs::span_of_point<dim>(breaks, cell->center());
                const Tensor<1, dim> h     = span_lengths(span);
                double               hface = 1.;
                for (unsigned int e = 0; e < dim; ++e)
                  if (e != d)
                    hface *= h[e];
                evaluate_cell(span, face_ref, ev);
                for (unsigned int q = 0; q < face_ref.size(); ++q)
                  {
                    const double dA =
                      face_measure_and_normal(face, ev.jacobians[q]).first *
                      hface * face_w[q];
                    if (points_out != nullptr)
                      {
                        points_out->push_back(ev.parametric_points[q]);
                        weights_out->push_back(dA);
                      }
                    else
                      for (unsigned int l = 0; l < ev.control_points.size();
                           ++l)
                        {
                          const auto it = local_of.find(ev.control_points[l]);
                          if (it != local_of.end())
                            integrals[it->second] += ev.values[q][l] * dA;
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
              coords[e] = breaks[e];
          xis = nurbs::tensor_product_points<dim>(coords);
        }

      std::vector<SurfacePoint<dim>> result(xis.size());
      for (unsigned int i = 0; i < xis.size(); ++i)
        {
          result[i].parametric = xis[i];
          result[i].location   = geometry.value(xis[i]);
          result[i].normal =
            face_measure_and_normal(face, geometry.jacobian(xis[i])).second;
          result[i].op = parametric_point_operator(xis[i]);
        }

      if (placement == PairPlacement::gauss)
        {
          for (unsigned int i = 0; i < xis.size(); ++i)
            result[i].tributary_area = qweights[i];
          return result;
        }

      integrate(n_quadrature_points_1d() + 1, nullptr, nullptr);
      Eigen::MatrixXd M = Eigen::MatrixXd::Zero(face_cps.size(), xis.size());
      for (unsigned int i = 0; i < xis.size(); ++i)
        for (unsigned int k = 0; k < result[i].op.weights.size(); ++k)
          {
            const auto it = local_of.find(result[i].op.dofs[k][0] / dim);
            if (it != local_of.end())
              M(it->second, i) += result[i].op.weights[k];
          }
      Eigen::VectorXd areas;
      if (placement == PairPlacement::greville)
        {
          Eigen::FullPivLU<Eigen::MatrixXd> lu(M);
          AssertThrow(lu.isInvertible(),
                      ExcMessage("Body '" + this->body_description.name +
                                 "': the Greville collocation matrix of face " +
                                 std::to_string(face) +
                                 " is singular; this should not happen."));
          areas = lu.solve(integrals);
        }
      else
        areas = M.completeOrthogonalDecomposition().solve(integrals);
      for (unsigned int i = 0; i < xis.size(); ++i)
        result[i].tributary_area = areas[i];
      return result;
    }



    template <int dim>
    ErrorNorms
    IgaBody<dim>::compute_errors(const Vector<double>     &u,
                                 const ExactSolution<dim> &exact) const
    {
      AssertThrow(static_cast<bool>(exact.displacement),
                  ExcMessage("compute_errors: the exact solution has no "
                             "displacement function."));
      AssertDimension(u.size(), this->n_unknowns);
      const SymmetricTensor<4, dim> C =
        this->body_description.material.stiffness();
      const SymmetricTensor<4, dim> S = invert(C);
      const QGauss<dim>             quadrature(max_degree() + 3);
      const bool with_stress = static_cast<bool>(exact.stress);

      double         e_l2 = 0., u_l2 = 0., e_en = 0., u_en = 0., vol = 0.;
      CellEvaluation ev;
      for (const auto &cell : parametric_mesh.active_cell_iterators())
        {
          const auto span = nurbs::span_of_point<dim>(breaks, cell->center());
          const Tensor<1, dim> h     = span_lengths(span);
          double               hprod = 1.;
          for (unsigned int d = 0; d < dim; ++d)
            hprod *= h[d];
          evaluate_cell(span, quadrature.get_points(), ev);
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              const Tensor<2, dim> &J = ev.jacobians[q];
              const double          JxW =
                std::abs(determinant(J)) * hprod * quadrature.weight(q);
              const Tensor<2, dim>    Jinv = invert(J);
              Tensor<1, dim>          uh;
              SymmetricTensor<2, dim> eps;
              for (unsigned int l = 0; l < ev.control_points.size(); ++l)
                {
                  const Tensor<1, dim> g =
                    transpose(Jinv) * ev.parametric_gradients[q][l];
                  for (unsigned int c = 0; c < dim; ++c)
                    {
                      const double uc = u[dim * ev.control_points[l] + c];
                      uh[c] += ev.values[q][l] * uc;
                      eps += uc * basis_strain<dim>(g, c);
                    }
                }
              const Tensor<1, dim> ue = exact.displacement(ev.points[q]);
              e_l2 += (ue - uh).norm_square() * JxW;
              u_l2 += ue.norm_square() * JxW;
              vol += JxW;
              if (with_stress)
                {
                  const SymmetricTensor<2, dim> se = exact.stress(ev.points[q]);
                  const SymmetricTensor<2, dim> ds = se - C * eps;
                  e_en += (ds * (S * ds)) * JxW;
                  u_en += (se * (S * se)) * JxW;
                }
            }
        }
      ErrorNorms result;
      result.l2_relative     = std::sqrt(e_l2 / std::max(u_l2, 1e-300));
      result.energy_relative = with_stress ?
                                 std::sqrt(e_en / std::max(u_en, 1e-300)) :
                                 std::numeric_limits<double>::quiet_NaN();
      result.measure         = vol;
      return result;
    }



    template <int dim>
    SymmetricTensor<2, dim>
    IgaBody<dim>::strain_at_parametric(const Vector<double> &u,
                                       const Point<dim>     &xi_in) const
    {
      AssertDimension(u.size(), this->n_unknowns);
      // Where the map is singular (a collapsed corner, or two faces meeting
      // at a straight angle) the strain is the limit from inside: step
      // towards the centre of the parametric box until J is regular.
      const Point<dim> lo     = geometry.parametric_lower();
      const Point<dim> hi     = geometry.parametric_upper();
      const Point<dim> centre = 0.5 * (lo + hi);
      Point<dim>       xi     = xi_in;
      Tensor<2, dim>   J      = geometry.jacobian(xi);
      for (unsigned int k = 0; k < 8; ++k)
        {
          const double scale = std::pow(J.norm(), dim);
          if (std::abs(determinant(J)) > 1e-10 * scale && scale > 0.)
            break;
          xi = xi + std::pow(10., -8. + k) * (centre - xi_in);
          J  = geometry.jacobian(xi);
        }
      std::vector<unsigned int>   indices;
      std::vector<double>         R;
      std::vector<Tensor<1, dim>> dR;
      geometry.basis(xi, indices, R, &dR);
      const Tensor<2, dim>    Jinv = invert(J);
      SymmetricTensor<2, dim> eps;
      for (unsigned int l = 0; l < indices.size(); ++l)
        {
          const Tensor<1, dim> g = transpose(Jinv) * dR[l];
          for (unsigned int c = 0; c < dim; ++c)
            eps += u[dim * indices[l] + c] * basis_strain<dim>(g, c);
        }
      return eps;
    }



    template <int dim>
    SymmetricTensor<2, dim>
    IgaBody<dim>::stress(const Vector<double> &u,
                         const Point<dim>     &location) const
    {
      return this->body_description.material.stiffness() *
             strain_at_parametric(u, parametric_point(location));
    }



    template <int dim>
    double
    IgaBody<dim>::measure() const
    {
      // Affine (polynomial) patches are integrated exactly by p+1 points;
      // rational ones need many more for round-off accuracy.
      const bool        rational = n_quadrature_points_1d() > max_degree() + 1;
      const QGauss<dim> quadrature(rational ? std::max(max_degree() + 1, 12u) :
                                              max_degree() + 1);
      double            vol = 0.;
      CellEvaluation    ev;
      for (const auto &cell : parametric_mesh.active_cell_iterators())
        {
          const auto span = nurbs::span_of_point<dim>(breaks, cell->center());
          const Tensor<1, dim> h     = span_lengths(span);
          double               hprod = 1.;
          for (unsigned int d = 0; d < dim; ++d)
            hprod *= h[d];
          evaluate_cell(span, quadrature.get_points(), ev);
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            vol += std::abs(determinant(ev.jacobians[q])) * hprod *
                   quadrature.weight(q);
        }
      return vol;
    }



    template <int dim>
    void
    IgaBody<dim>::write_vtu(const Vector<double> &u,
                            const std::string    &filename) const
    {
      AssertDimension(u.size(), this->n_unknowns);
      const unsigned int n_sub =
        std::max(1u, this->settings.output_subdivisions);
      const SymmetricTensor<4, dim> C =
        this->body_description.material.stiffness();
      const auto  &material = this->body_description.material;
      const double nu       = material.poisson_ratio;
      const bool   plane_strain =
        (dim == 2 &&
         material.plane_model == elasticity::PlaneModel::plane_strain);

      // Output points: lexicographic (n+1)^dim grid on [0, 1]^dim.
      std::vector<Point<dim>> ref;
      {
        const unsigned int n1 = n_sub + 1;
        unsigned int       n  = 1;
        for (unsigned int d = 0; d < dim; ++d)
          n *= n1;
        ref.resize(n);
        for (unsigned int s = 0; s < n; ++s)
          {
            unsigned int rest = s;
            for (unsigned int d = 0; d < dim; ++d)
              {
                ref[s][d] = static_cast<double>(rest % n1) / n_sub;
                rest /= n1;
              }
          }
      }

      static const char       *axis = "xyz";
      std::vector<std::string> names;
      for (unsigned int c = 0; c < dim; ++c)
        names.emplace_back("displacement");
      std::vector<std::pair<unsigned int, unsigned int>> comps;
      for (unsigned int i = 0; i < dim; ++i)
        comps.emplace_back(i, i);
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = i + 1; j < dim; ++j)
          comps.emplace_back(i, j);
      for (const auto &[i, j] : comps)
        names.push_back(std::string("strain_") + axis[i] + axis[j]);
      for (const auto &[i, j] : comps)
        names.push_back(std::string("stress_") + axis[i] + axis[j]);
      names.emplace_back("von_mises");
      const unsigned int n_data = names.size();

      std::vector<DataOutBase::Patch<dim, dim>> patches;
      CellEvaluation                            ev;
      unsigned int                              index = 0;
      for (const auto &cell : parametric_mesh.active_cell_iterators())
        {
          const auto span = nurbs::span_of_point<dim>(breaks, cell->center());
          evaluate_cell(span, ref, ev);
          DataOutBase::Patch<dim, dim> patch;
          patch.n_subdivisions       = n_sub;
          patch.points_are_available = true;
          patch.patch_index          = index++;
          patch.reference_cell       = ReferenceCells::get_hypercube<dim>();
          for (unsigned int v = 0; v < GeometryInfo<dim>::vertices_per_cell;
               ++v)
            {
              unsigned int s = 0, stride = 1;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  s += ((v >> d) & 1u) * n_sub * stride;
                  stride *= n_sub + 1;
                }
              patch.vertices[v] = ev.points[s];
            }
          patch.data.reinit(n_data + dim, ref.size());
          for (unsigned int q = 0; q < ref.size(); ++q)
            {
              const Tensor<2, dim>   &J    = ev.jacobians[q];
              const double            detJ = determinant(J);
              Tensor<1, dim>          uh;
              SymmetricTensor<2, dim> eps;
              const bool              regular =
                std::abs(detJ) > 1e-10 * std::pow(J.norm(), dim);
              const Tensor<2, dim> Jinv =
                regular ? invert(J) : Tensor<2, dim>();
              for (unsigned int l = 0; l < ev.control_points.size(); ++l)
                {
                  const Tensor<1, dim> g =
                    transpose(Jinv) * ev.parametric_gradients[q][l];
                  for (unsigned int c = 0; c < dim; ++c)
                    {
                      const double uc = u[dim * ev.control_points[l] + c];
                      uh[c] += ev.values[q][l] * uc;
                      if (regular)
                        eps += uc * basis_strain<dim>(g, c);
                    }
                }
              if (!regular)
                eps = strain_at_parametric(u, ev.parametric_points[q]);
              const SymmetricTensor<2, dim> sigma = C * eps;
              // Von Mises with the out-of-plane stress of plane strain.
              const double s33 =
                plane_strain ? nu * (sigma[0][0] + sigma[1][1]) : 0.;
              const double tr = trace(sigma) + s33;
              double       j2 = 0.;
              for (unsigned int i = 0; i < dim; ++i)
                for (unsigned int j = 0; j < dim; ++j)
                  {
                    const double dev = sigma[i][j] - (i == j ? tr / 3. : 0.);
                    j2 += dev * dev;
                  }
              if (dim == 2)
                j2 += (s33 - tr / 3.) * (s33 - tr / 3.);
              const double vm = std::sqrt(1.5 * j2);

              unsigned int row = 0;
              for (unsigned int c = 0; c < dim; ++c)
                patch.data(row++, q) = uh[c];
              for (const auto &[i, j] : comps)
                patch.data(row++, q) = eps[i][j];
              for (const auto &[i, j] : comps)
                patch.data(row++, q) = sigma[i][j];
              patch.data(row++, q) = vm;
              for (unsigned int d = 0; d < dim; ++d)
                patch.data(row++, q) = ev.points[q][d];
            }
          patches.push_back(std::move(patch));
        }

      std::vector<
        std::tuple<unsigned int,
                   unsigned int,
                   std::string,
                   DataComponentInterpretation::DataComponentInterpretation>>
        ranges;
      ranges.emplace_back(
        0,
        dim - 1,
        "displacement",
        DataComponentInterpretation::component_is_part_of_vector);
      std::ofstream out(filename);
      AssertThrow(out,
                  ExcMessage("Body '" + this->body_description.name +
                             "': cannot open '" + filename +
                             "' for writing; does its directory exist?"));
      DataOutBase::VtkFlags flags;
      DataOutBase::write_vtu(patches, names, ranges, flags, out);
    }



    template <int dim>
    SurfacePoint<dim>
    IgaBody<dim>::closest_surface_point(const types::boundary_id face,
                                        const Point<dim>        &location,
                                        const SurfacePoint<dim> &) const
    {
      const Point<dim>  xi = patch().closest_point_on_face(face, location);
      SurfacePoint<dim> point;
      point.parametric = xi;
      point.location   = patch().value(xi);
      point.normal     = patch().outward_normal(face, xi);
      point.op         = parametric_point_operator(xi);
      return point;
    }



    template class IgaBody<2>;
    template class IgaBody<3>;
  } // namespace discretization
} // namespace igabde
