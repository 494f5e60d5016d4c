#include <igabde/discretization/rigid_modes.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace igabde
{
  namespace discretization
  {
    namespace
    {
      constexpr unsigned int
      n_pure_modes(const int dim)
      {
        return dim == 2 ? 3 : 6;
      }
    } // namespace



    template <int dim>
    RigidModes<dim>::RigidModes(const std::vector<Point<dim>>   &locations,
                                const std::vector<unsigned int> &components,
                                const AffineConstraints<double> &constraints)
      : locations(locations)
      , components(components)
      , constrained(locations.size(), false)
    {
      AssertDimension(components.size(), locations.size());
      const std::size_t n = locations.size();
      for (std::size_t i = 0; i < n; ++i)
        constrained[i] = constraints.is_constrained(i);

      // Rotations about the centroid, scaled by the body size, so that all
      // modes have entries of order one.
      for (const auto &x : locations)
        mode_centre += x;
      if (n > 0)
        mode_centre /= static_cast<double>(n);
      mode_size = 0.;
      for (const auto &x : locations)
        mode_size = std::max(mode_size, (x - mode_centre).norm());
      mode_size = std::max(mode_size, 1e-300);

      std::vector<std::size_t> rows;
      for (std::size_t i = 0; i < n; ++i)
        if (constrained[i])
          rows.push_back(i);
      const unsigned int n_modes = n_pure_modes(dim);
      Eigen::MatrixXd    M(std::max<std::size_t>(rows.size(), 1), n_modes);
      M.setZero();
      for (unsigned int r = 0; r < rows.size(); ++r)
        for (unsigned int m = 0; m < n_modes; ++m)
          M(r, m) = pure_mode_value(m, rows[r]);

      // The null space of M: the right singular vectors of (numerically)
      // zero singular values.
      Eigen::JacobiSVD<Eigen::MatrixXd> svd(M, Eigen::ComputeFullV);
      const Eigen::VectorXd            &s = svd.singularValues();
      for (unsigned int m = 0; m < n_modes; ++m)
        {
          const double sigma = (m < s.size() ? s(m) : 0.);
          if (sigma < 1e-8 * std::max(1., std::sqrt(double(rows.size()))))
            {
              const Eigen::VectorXd v = svd.matrixV().col(m);
              free_coefficients.emplace_back(v.data(), v.data() + v.size());
            }
        }
      build_free_modes();
    }



    template <int dim>
    const std::vector<Vector<double>> &
    RigidModes<dim>::free_modes() const
    {
      return free;
    }



    template <int dim>
    const std::vector<std::string> &
    RigidModes<dim>::free_mode_names() const
    {
      return free_names;
    }



    template <int dim>
    bool
    RigidModes<dim>::free_translation(const unsigned int c) const
    {
      AssertIndexRange(c, dim);
      // The free modes' coefficients are orthonormal: the translation along
      // c lies in their span when its projection on them has unit length.
      double projection = 0.;
      for (const auto &v : free_coefficients)
        projection += v[c] * v[c];
      return projection > 1. - 1e-8;
    }



    template <int dim>
    std::vector<types::global_dof_index>
    RigidModes<dim>::pins(const std::vector<double> &weights) const
    {
      std::vector<types::global_dof_index> result;
      if (free.empty())
        return result;
      const std::size_t n = locations.size();
      AssertDimension(weights.size(), n);
      Eigen::MatrixXd Rt(free.size(), n);
      for (unsigned int k = 0; k < free.size(); ++k)
        for (std::size_t i = 0; i < n; ++i)
          Rt(k, i) = weights[i] * free[k][i];
      Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Rt);
      const auto &perm = qr.colsPermutation().indices();
      for (unsigned int k = 0; k < free.size(); ++k)
        {
          Assert(!constrained[perm(k)], ExcInternalError());
          result.push_back(perm(k));
        }
      return result;
    }



    template <int dim>
    void
    RigidModes<dim>::hold(const std::vector<Vector<double>> &c,
                          const FullMatrix<double>          &J)
    {
      held.clear();
      loads.clear();
      held_names.clear();
      moments.clear();
      inverse.reinit(0, 0);
      if (free.empty())
        return;
      const unsigned int n_axes = c.size();
      AssertDimension(J.m(), n_axes);
      AssertDimension(J.n(), n_axes);

      // The free modes the constraints c_a^T u = 0 hold: A = C^T R on the
      // free modes, A = U Sigma V^T; the first r right singular vectors are
      // held (with the combinations c U of the constraints), the others
      // stay free.
      const unsigned int n_free = free.size();
      Eigen::MatrixXd    A(n_axes, n_free);
      double             c_norm = 0., r_norm = 0.;
      for (unsigned int a = 0; a < n_axes; ++a)
        {
          c_norm = std::max(c_norm, c[a].l2_norm());
          for (unsigned int j = 0; j < n_free; ++j)
            A(a, j) = c[a] * free[j];
        }
      for (const auto &r : free)
        r_norm = std::max(r_norm, r.l2_norm());
      Eigen::JacobiSVD<Eigen::MatrixXd> svd(A,
                                            Eigen::ComputeFullU |
                                              Eigen::ComputeFullV);
      unsigned int                      rank = 0;
      while (rank < svd.singularValues().size() &&
             svd.singularValues()(rank) > 1e-8 * c_norm * r_norm)
        ++rank;

      const unsigned int n_modes = n_pure_modes(dim);
      const auto         combine = [&](const unsigned int column) {
        std::vector<double> v(n_modes, 0.);
        for (unsigned int j = 0; j < n_free; ++j)
          for (unsigned int m = 0; m < n_modes; ++m)
            v[m] += svd.matrixV()(j, column) * free_coefficients[j][m];
        return v;
      };
      std::vector<std::vector<double>> still_free;
      for (unsigned int k = 0; k < n_free; ++k)
        if (k < rank)
          {
            auto [held_mode, name] = mode(combine(k));
            held.push_back(std::move(held_mode));
            held_names.push_back(std::move(name));
            Vector<double>      load(locations.size());
            std::vector<double> moment(n_axes, 0.);
            for (unsigned int a = 0; a < n_axes; ++a)
              {
                load.add(svd.matrixU()(a, k), c[a]);
                for (unsigned int b = 0; b < n_axes; ++b)
                  moment[b] += svd.matrixU()(a, k) * J(a, b);
              }
            loads.push_back(std::move(load));
            moments.push_back(std::move(moment));
          }
        else
          still_free.push_back(combine(k));
      free_coefficients = still_free;
      build_free_modes();

      // S = R_h^T C_h (diagonal Sigma up to round-off), inverted.
      inverse.reinit(rank, rank);
      for (unsigned int k = 0; k < rank; ++k)
        for (unsigned int l = 0; l < rank; ++l)
          inverse(k, l) = held[k] * loads[l];
      if (rank > 0)
        inverse.gauss_jordan();
    }



    template <int dim>
    const std::vector<Vector<double>> &
    RigidModes<dim>::held_modes() const
    {
      return held;
    }



    template <int dim>
    const std::vector<Vector<double>> &
    RigidModes<dim>::held_loads() const
    {
      return loads;
    }



    template <int dim>
    const FullMatrix<double> &
    RigidModes<dim>::held_inverse() const
    {
      return inverse;
    }



    template <int dim>
    const std::vector<std::string> &
    RigidModes<dim>::held_mode_names() const
    {
      return held_names;
    }



    template <int dim>
    Vector<double>
    RigidModes<dim>::held_multipliers(const Vector<double> &f) const
    {
      const unsigned int r = held.size();
      Vector<double>     rf(r), lambda(r);
      for (unsigned int k = 0; k < r; ++k)
        rf[k] = held[k] * f;
      if (r > 0)
        inverse.vmult(lambda, rf);
      return lambda;
    }



    template <int dim>
    void
    RigidModes<dim>::balance(Vector<double> &f) const
    {
      const Vector<double> lambda = held_multipliers(f);
      for (unsigned int k = 0; k < lambda.size(); ++k)
        f.add(-lambda[k], loads[k]);
    }



    template <int dim>
    void
    RigidModes<dim>::fix(Vector<double> &u) const
    {
      const unsigned int r = held.size();
      if (r == 0)
        return;
      Vector<double> cu(r), beta(r);
      for (unsigned int k = 0; k < r; ++k)
        cu[k] = loads[k] * u;
      inverse.Tvmult(beta, cu);
      for (unsigned int k = 0; k < r; ++k)
        u.add(-beta[k], held[k]);
    }



    template <int dim>
    std::vector<double>
    RigidModes<dim>::held_moment(const Vector<double> &f) const
    {
      const Vector<double> lambda = held_multipliers(f);
      std::vector<double>  moment(dim == 2 ? 1 : 3, 0.);
      for (unsigned int k = 0; k < lambda.size(); ++k)
        for (unsigned int b = 0; b < moment.size(); ++b)
          moment[b] -= lambda[k] * moments[k][b];
      return moment;
    }



    template <int dim>
    const Point<dim> &
    RigidModes<dim>::centre() const
    {
      return mode_centre;
    }



    template <int dim>
    double
    RigidModes<dim>::size() const
    {
      return mode_size;
    }



    template <int dim>
    double
    RigidModes<dim>::pure_mode_value(const unsigned int mode,
                                     const std::size_t  i) const
    {
      const unsigned int   c = components[i];
      const Tensor<1, dim> x = (locations[i] - mode_centre) / mode_size;
      if (mode < dim)
        return (c == mode ? 1. : 0.);
      // Rotation about axis a (3D) or about z (2D): u = e_a x x.
      Tensor<1, dim> u;
      if (dim == 2)
        {
          u[0] = -x[1];
          u[1] = x[0];
        }
      else
        {
          const unsigned int a = mode - dim;
          const unsigned int b = (a + 1) % 3, d = (a + 2) % 3;
          u[b] = -x[d];
          u[d] = x[b];
        }
      return u[c];
    }



    template <int dim>
    std::pair<Vector<double>, std::string>
    RigidModes<dim>::mode(const std::vector<double> &coefficients) const
    {
      const unsigned int n_modes = n_pure_modes(dim);
      AssertDimension(coefficients.size(), n_modes);
      Vector<double> values(locations.size());
      for (std::size_t i = 0; i < locations.size(); ++i)
        if (!constrained[i])
          for (unsigned int m = 0; m < n_modes; ++m)
            values[i] += coefficients[m] * pure_mode_value(m, i);

      static const char *names2[] = {"translation x",
                                     "translation y",
                                     "rotation z"};
      static const char *names3[] = {"translation x",
                                     "translation y",
                                     "translation z",
                                     "rotation x",
                                     "rotation y",
                                     "rotation z"};
      unsigned int       dominant = 0;
      double             norm     = 0.;
      for (unsigned int m = 0; m < n_modes; ++m)
        {
          norm += coefficients[m] * coefficients[m];
          if (std::abs(coefficients[m]) > std::abs(coefficients[dominant]))
            dominant = m;
        }
      const bool pure = std::abs(std::abs(coefficients[dominant]) -
                                 std::sqrt(norm)) < 1e-10 * std::sqrt(norm);
      return {values,
              std::string(dim == 2 ? names2[dominant] : names3[dominant]) +
                (pure ? "" : " (combined)")};
    }



    template <int dim>
    void
    RigidModes<dim>::build_free_modes()
    {
      free.clear();
      free_names.clear();
      for (const auto &v : free_coefficients)
        {
          auto [free_mode, name] = mode(v);
          free.push_back(std::move(free_mode));
          free_names.push_back(std::move(name));
        }
    }



    template class RigidModes<2>;
    template class RigidModes<3>;
  } // namespace discretization
} // namespace igabde
