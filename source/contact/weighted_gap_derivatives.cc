#include <igabde/contact/weighted_gap_derivatives.h>

#include <algorithm>
#include <cmath>
#include <functional>

// The integrals of WeightedGapPairing at a slave quadrature point x_s(eta)
// (fixed face coordinates) facing the master point x_m(xi):
//   dA = w |x_s,eta| (the slave measure), g = (x_s - x_m) . n(xi),
//   n(xi) the master's unit normal, R_B(xi) the master operator,
// and xi the closest point: t_a(xi) . (x_s - x_m(xi)) = 0. Its derivative
// by the unknowns z of both bodies, with r = x_s - x_m,
//   H dxi = t_a . (dx_s - sum_B R_B dz_B) + r . sum_B R_B,a dz_B,
//   H_ab = t_a . t_b - r . t_a,b,
// held at zero in a coordinate that the projection clamps to the face's
// bound; then dx_m = sum_B R_B dz_B + t_b dxi_b, dt_a = sum_B R_B,a dz_B +
// t_a,b dxi_b, dn = (I - n n) d(t_0 x t_1) / |t_0 x t_1| (2D: t_0 turned),
// dg = (dx_s - dx_m) . n + r . dn.

namespace igabde
{
  namespace contact
  {
    namespace internal
    {
      template <int dim>
      void
      IntegralDerivatives<dim>::add(const IntegralDerivatives &other)
      {
        const auto merge = [](Map &to, const Map &from) {
          for (const auto &[u, v] : from)
            to[u] += v;
        };
        merge(area, other.area);
        merge(gap, other.gap);
        for (unsigned int c = 0; c < dim; ++c)
          merge(normal[c], other.normal[c]);
        for (const auto &[key, row] : other.op1)
          merge(op1[key], row);
        for (const auto &[key, row] : other.op2)
          merge(op2[key], row);
      }



      namespace
      {
        /// The derivatives by the face coordinates of a face point's
        /// operator weights (@p dw, per entry of its operator) and tangents
        /// (@p dt[a][b] = d t_a / d eta_b), by central differences with
        /// steps @p h inside the box [@p lower, @p upper].
        template <int dim>
        void
        face_derivatives(
          const std::function<
            discretization::FacePoint<dim>(const Point<dim - 1> &)> &at,
          const Point<dim - 1>                                      &eta,
          const discretization::PointOperator<dim>                  &op,
          const Point<dim - 1>                                      &h,
          const Point<dim - 1>                                      &lower,
          const Point<dim - 1>                                      &upper,
          std::vector<std::array<double, dim - 1>>                  &dw,
          std::array<std::array<Tensor<1, dim>, dim - 1>, dim - 1>  &dt)
        {
          dw.assign(op.weights.size(), std::array<double, dim - 1>());
          for (unsigned int b = 0; b + 1 < dim; ++b)
            {
              Point<dim - 1> up = eta, down = eta;
              up[b]   = std::min(eta[b] + h[b], upper[b]);
              down[b] = std::max(eta[b] - h[b], lower[b]);
              const auto                                pu   = at(up);
              const auto                                pd   = at(down);
              const double                              step = up[b] - down[b];
              std::map<types::global_dof_index, double> wu, wd;
              for (unsigned int k = 0; k < pu.op.weights.size(); ++k)
                wu[pu.op.dofs[k][0]] = pu.op.weights[k];
              for (unsigned int k = 0; k < pd.op.weights.size(); ++k)
                wd[pd.op.dofs[k][0]] = pd.op.weights[k];
              for (unsigned int k = 0; k < op.weights.size(); ++k)
                {
                  const auto key = op.dofs[k][0];
                  const auto iu  = wu.find(key);
                  const auto id  = wd.find(key);
                  dw[k][b]       = ((iu != wu.end() ? iu->second : 0.) -
                              (id != wd.end() ? id->second : 0.)) /
                             step;
                }
              for (unsigned int a = 0; a + 1 < dim; ++a)
                dt[a][b] = (pu.tangents[a] - pd.tangents[a]) / step;
            }
        }



        /// d n for a change @p dt of the tangents of a face with unit
        /// normal @p n and tangents @p t.
        template <int dim>
        Tensor<1, dim>
        normal_change(const Tensor<1, dim>                      &n,
                      const std::array<Tensor<1, dim>, dim - 1> &t,
                      const std::array<Tensor<1, dim>, dim - 1> &dt)
        {
          Tensor<1, dim> a, da;
          if constexpr (dim == 2)
            {
              a[0]  = t[0][1];
              a[1]  = -t[0][0];
              da[0] = dt[0][1];
              da[1] = -dt[0][0];
            }
          else
            {
              a = cross_product_3d(t[0], t[1]);
              da =
                cross_product_3d(dt[0], t[1]) + cross_product_3d(t[0], dt[1]);
            }
          const double length = a.norm();
          const double sign   = a * n > 0. ? 1. : -1.;
          Assert((sign * a / length - n).norm() < 1e-8, ExcInternalError());
          const Tensor<1, dim> v = sign * da / length;
          return v - (v * n) * n;
        }



        /// The element's slave unknowns' derivatives of its dual basis
        /// A = D M^{-1} (element_dual_basis() of weighted_gap_pairing.cc:
        /// M_jk = int_e N_j N_k, D = diag(int_e N_j) on the element's
        /// uncut @p rule, functions without a share on the face held by an
        /// identity row): dA = (dD - A dM) M^{-1}, one matrix per slave
        /// unknown (the first @p n_slave of @p index).
        template <int dim>
        std::vector<Eigen::MatrixXd>
        dual_derivatives(
          const discretization::Body<dim>                       &slave_body,
          const types::boundary_id                               slave_face,
          const Point<dim - 1>                                  &lo,
          const Point<dim - 1>                                  &hi,
          const QGauss<1>                                       &rule,
          const std::map<types::global_dof_index, unsigned int> &local,
          const Eigen::MatrixXd                                 &dual,
          const std::map<typename PairDerivatives<dim>::Unknown, unsigned int>
                            &index,
          const unsigned int n_slave)
        {
          constexpr unsigned int       fd = dim - 1;
          const unsigned int           n  = local.size();
          Eigen::MatrixXd              M  = Eigen::MatrixXd::Zero(n, n);
          Eigen::VectorXd              D  = Eigen::VectorXd::Zero(n);
          std::vector<Eigen::MatrixXd> dM(n_slave, Eigen::MatrixXd::Zero(n, n));
          std::vector<Eigen::VectorXd> dD(n_slave, Eigen::VectorXd::Zero(n));
          double                       element_area = 0.;
          unsigned int                 nq           = 1;
          for (unsigned int k = 0; k < fd; ++k)
            nq *= rule.size();
          const auto at = [&](const Point<fd> &eta) {
            return slave_body.face_point(slave_face, eta);
          };
          Point<fd> h;
          for (unsigned int k = 0; k < fd; ++k)
            h[k] = 1e-6 * (hi[k] - lo[k]);
          for (unsigned int q = 0; q < nq; ++q)
            {
              Point<fd>    eta;
              double       weight = 1.;
              unsigned int qr     = q;
              for (unsigned int k = 0; k < fd; ++k)
                {
                  const unsigned int iq = qr % rule.size();
                  qr /= rule.size();
                  eta[k] = lo[k] + (hi[k] - lo[k]) * rule.point(iq)[0];
                  weight *= (hi[k] - lo[k]) * rule.weight(iq);
                }
              const auto                                     s = at(eta);
              std::vector<std::array<double, fd>>            dN;
              std::array<std::array<Tensor<1, dim>, fd>, fd> unused;
              face_derivatives<dim>(at, eta, s.op, h, lo, hi, dN, unused);
              const double dA = weight * s.measure;
              element_area += dA;
              Eigen::VectorXd N      = Eigen::VectorXd::Zero(n);
              Eigen::VectorXd d_meas = Eigen::VectorXd::Zero(n_slave);
              Tensor<1, dim>  unit;
              if constexpr (dim == 3)
                unit =
                  cross_product_3d(s.tangents[0], s.tangents[1]) / s.measure;
              for (unsigned int a = 0; a < s.op.weights.size(); ++a)
                {
                  if (s.op.weights[a] == 0.)
                    continue;
                  N(local.at(s.op.dofs[a][0])) = s.op.weights[a];
                  for (unsigned int c = 0; c < dim; ++c)
                    {
                      const unsigned int l = index.at({0u, s.op.dofs[a][c]});
                      if constexpr (dim == 2)
                        d_meas(l) += dN[a][0] * s.tangents[0][c] / s.measure;
                      else
                        d_meas(l) +=
                          dN[a][0] * cross_product_3d(s.tangents[1], unit)[c] +
                          dN[a][1] * cross_product_3d(unit, s.tangents[0])[c];
                    }
                }
              M += dA * N * N.transpose();
              D += dA * N;
              for (unsigned int l = 0; l < n_slave; ++l)
                if (d_meas(l) != 0.)
                  {
                    dM[l] += weight * d_meas(l) * N * N.transpose();
                    dD[l] += weight * d_meas(l) * N;
                  }
            }
          for (unsigned int j = 0; j < n; ++j)
            if (D(j) <= 1e-12 * element_area)
              {
                M.row(j).setZero();
                M.col(j).setZero();
                M(j, j) = 1.;
                D(j)    = 0.;
                for (unsigned int l = 0; l < n_slave; ++l)
                  {
                    dM[l].row(j).setZero();
                    dM[l].col(j).setZero();
                    dD[l](j) = 0.;
                  }
              }
          const Eigen::MatrixXd M_inverse = M.inverse();
          Assert((D.asDiagonal() * M_inverse - dual).norm() <=
                   1e-8 * (1. + dual.norm()),
                 ExcInternalError());
          std::vector<Eigen::MatrixXd> result(n_slave);
          for (unsigned int l = 0; l < n_slave; ++l)
            result[l] =
              (Eigen::MatrixXd(dD[l].asDiagonal()) - dual * dM[l]) * M_inverse;
          return result;
        }
      } // namespace



      template <int dim>
      void
      add_element_derivatives(
        const discretization::Body<dim>                       &slave_body,
        const types::boundary_id                               slave_face,
        const MasterSide<dim>                                 &master,
        const Point<dim - 1>                                  &lo,
        const Point<dim - 1>                                  &hi,
        const std::vector<ElementSample<dim>>                 &samples,
        const QGauss<1>                                       &rule,
        const std::map<types::global_dof_index, unsigned int> &local,
        const Eigen::MatrixXd                                 &dual,
        std::map<types::global_dof_index, IntegralDerivatives<dim>>
          &derivatives)
      {
        constexpr unsigned int fd = dim - 1;
        using Unknown             = typename PairDerivatives<dim>::Unknown;
        if (samples.empty())
          return;
        const bool deformable = !master.projectors.empty();
        const bool dual_basis = dual.size() > 0;

        // The element's unknowns: the slave's first (its functions on the
        // element), then the master's at the samples.
        std::map<Unknown, unsigned int> index;
        std::vector<Unknown>            unknowns;
        const auto                      number = [&](const Unknown &u) {
          const auto [it, added] = index.emplace(u, unknowns.size());
          if (added)
            unknowns.push_back(u);
          return it->second;
        };
        // The functions: the slave's (by key; in the dual's numbering
        // where it has one) and the master's.
        std::map<types::global_dof_index, unsigned int> slave_fn = local;
        std::map<types::global_dof_index, unsigned int> master_fn;
        for (const auto &sample : samples)
          for (unsigned int a = 0; a < sample.s.op.weights.size(); ++a)
            if (sample.s.op.weights[a] != 0.)
              {
                slave_fn.emplace(sample.s.op.dofs[a][0], slave_fn.size());
                for (unsigned int c = 0; c < dim; ++c)
                  number({0u, sample.s.op.dofs[a][c]});
              }
        const unsigned int n_slave = unknowns.size();
        for (const auto &sample : samples)
          for (unsigned int b = 0; b < sample.m.op.weights.size(); ++b)
            if (sample.m.op.weights[b] != 0.)
              {
                master_fn.emplace(sample.m.op.dofs[b][0], master_fn.size());
                for (unsigned int c = 0; c < dim; ++c)
                  number({1u, sample.m.op.dofs[b][c]});
              }
        const unsigned int n_loc = unknowns.size();
        const unsigned int n_f   = slave_fn.size();
        const unsigned int n_b   = master_fn.size();

        const std::vector<Eigen::MatrixXd> d_dual =
          dual_basis ? dual_derivatives<dim>(slave_body,
                                             slave_face,
                                             lo,
                                             hi,
                                             rule,
                                             local,
                                             dual,
                                             index,
                                             n_slave) :
                       std::vector<Eigen::MatrixXd>();

        // Per slave function f: the derivatives of its integrals, each
        // row a vector over the element's unknowns.
        std::vector<Eigen::VectorXd> d_area(n_f, Eigen::VectorXd::Zero(n_loc));
        std::vector<Eigen::VectorXd> d_gap(n_f, Eigen::VectorXd::Zero(n_loc));
        std::vector<Eigen::MatrixXd> d_normal(n_f,
                                              Eigen::MatrixXd::Zero(dim,
                                                                    n_loc));
        std::vector<Eigen::MatrixXd> d_op1(n_f,
                                           Eigen::MatrixXd::Zero(n_f, n_loc));
        std::vector<Eigen::MatrixXd> d_op2(n_f,
                                           Eigen::MatrixXd::Zero(n_b, n_loc));

        const auto slave_at = [&](const Point<fd> &eta) {
          return slave_body.face_point(slave_face, eta);
        };
        Point<fd> h_slave;
        double    element_size = 0.;
        for (unsigned int k = 0; k < fd; ++k)
          {
            h_slave[k] = 1e-6 * (hi[k] - lo[k]);
            element_size +=
              samples.front().s.tangents[k].norm() * (hi[k] - lo[k]);
          }

        for (const auto &sample : samples)
          {
            const auto          &s        = sample.s;
            const auto          &m        = sample.m;
            const double         dA_value = sample.weight * s.measure;
            const Tensor<1, dim> r        = s.location - m.location;
            const Tensor<1, dim> n        = m.normal;
            const double         g        = r * n;

            // The slave side: the measure's derivative (times the weight),
            // and x_s's (N_a in component c).
            std::vector<std::array<double, fd>>            dN;
            std::array<std::array<Tensor<1, dim>, fd>, fd> unused;
            face_derivatives<dim>(slave_at,
                                  sample.eta,
                                  s.op,
                                  h_slave,
                                  lo,
                                  hi,
                                  dN,
                                  unused);
            Eigen::VectorXd dA = Eigen::VectorXd::Zero(n_loc);
            Tensor<1, dim>  unit;
            if constexpr (dim == 3)
              unit = cross_product_3d(s.tangents[0], s.tangents[1]) / s.measure;
            // dx_s, dx_m and dn per unknown, and dxi.
            std::vector<Tensor<1, dim>> dxs(n_loc), dxm(n_loc), dn(n_loc);
            std::vector<Tensor<1, fd>>  dxi(n_loc);
            std::vector<unsigned int>   touched;
            for (unsigned int a = 0; a < s.op.weights.size(); ++a)
              {
                if (s.op.weights[a] == 0.)
                  continue;
                for (unsigned int c = 0; c < dim; ++c)
                  {
                    const unsigned int l = index.at({0u, s.op.dofs[a][c]});
                    touched.push_back(l);
                    dxs[l][c] += s.op.weights[a];
                    if constexpr (dim == 2)
                      dA(l) +=
                        sample.weight * dN[a][0] * s.tangents[0][c] / s.measure;
                    else
                      dA(l) +=
                        sample.weight *
                        (dN[a][0] * cross_product_3d(s.tangents[1], unit)[c] +
                         dN[a][1] * cross_product_3d(unit, s.tangents[0])[c]);
                  }
              }

            std::vector<std::array<double, fd>> dR;
            if (deformable)
              {
                // The master side at xi: R_B,a and t_a,b.
                const ContactSurface<dim> &part = *master.parts[sample.part];
                const auto &grid = master.projectors[sample.part]->grid;
                Point<fd>   h, lower, upper;
                std::array<bool, fd> held;
                for (unsigned int k = 0; k < fd; ++k)
                  {
                    const auto &breaks = grid.breaks[k];
                    lower[k]           = breaks.front();
                    upper[k]           = breaks.back();
                    // The element holding xi_k: [breaks[e - 1], breaks[e]].
                    std::size_t e = std::upper_bound(breaks.begin(),
                                                     breaks.end(),
                                                     sample.xi[k]) -
                                    breaks.begin();
                    e    = std::clamp<std::size_t>(e, 1, breaks.size() - 1);
                    h[k] = 1e-6 * (breaks[e] - breaks[e - 1]);
                    const double tol = 1e-12 * (upper[k] - lower[k]);
                    held[k]          = sample.xi[k] <= lower[k] + tol ||
                              sample.xi[k] >= upper[k] - tol;
                  }
                std::array<std::array<Tensor<1, dim>, fd>, fd> dt;
                face_derivatives<dim>(
                  [&](const Point<fd> &xi) {
                    return part.face_point(xi);
                  },
                  sample.xi,
                  m.op,
                  h,
                  lower,
                  upper,
                  dR,
                  dt);
                // H = T^T T - r . t_a,b, symmetric, on the free
                // coordinates.
                Tensor<2, fd> H;
                for (unsigned int a = 0; a < fd; ++a)
                  for (unsigned int b = 0; b < fd; ++b)
                    H[a][b] = m.tangents[a] * m.tangents[b] -
                              0.5 * (r * dt[a][b] + r * dt[b][a]);
                // Where the curvature term makes H indefinite (far from
                // the master), the projection's own Gauss-Newton matrix.
                if (!(H[0][0] > 0. && determinant(H) > 0.))
                  for (unsigned int a = 0; a < fd; ++a)
                    for (unsigned int b = 0; b < fd; ++b)
                      H[a][b] = m.tangents[a] * m.tangents[b];
                for (unsigned int k = 0; k < fd; ++k)
                  if (held[k])
                    for (unsigned int j = 0; j < fd; ++j)
                      {
                        H[k][j] = H[j][k] = 0.;
                        H[k][k]           = 1.;
                      }
                const Tensor<2, fd> H_inverse = invert(H);
                for (unsigned int b = 0; b < m.op.weights.size(); ++b)
                  {
                    if (m.op.weights[b] == 0.)
                      continue;
                    for (unsigned int c = 0; c < dim; ++c)
                      touched.push_back(index.at({1u, m.op.dofs[b][c]}));
                  }
                std::sort(touched.begin(), touched.end());
                touched.erase(std::unique(touched.begin(), touched.end()),
                              touched.end());
                // The right-hand side of H dxi per unknown, and the
                // unknowns' direct shares in dx_m and dt.
                std::vector<std::array<Tensor<1, dim>, fd>> dt_direct(n_loc);
                std::vector<Tensor<1, fd>>                  rhs(n_loc);
                for (unsigned int a = 0; a < s.op.weights.size(); ++a)
                  if (s.op.weights[a] != 0.)
                    for (unsigned int c = 0; c < dim; ++c)
                      {
                        const unsigned int l = index.at({0u, s.op.dofs[a][c]});
                        for (unsigned int k = 0; k < fd; ++k)
                          rhs[l][k] += s.op.weights[a] * m.tangents[k][c];
                      }
                for (unsigned int b = 0; b < m.op.weights.size(); ++b)
                  if (m.op.weights[b] != 0.)
                    for (unsigned int c = 0; c < dim; ++c)
                      {
                        const unsigned int l = index.at({1u, m.op.dofs[b][c]});
                        dxm[l][c] += m.op.weights[b];
                        for (unsigned int k = 0; k < fd; ++k)
                          {
                            rhs[l][k] += -m.op.weights[b] * m.tangents[k][c] +
                                         dR[b][k] * r[c];
                            dt_direct[l][k][c] += dR[b][k];
                          }
                      }
                for (const unsigned int l : touched)
                  {
                    Tensor<1, fd> b = rhs[l];
                    for (unsigned int k = 0; k < fd; ++k)
                      if (held[k])
                        b[k] = 0.;
                    dxi[l]                             = H_inverse * b;
                    std::array<Tensor<1, dim>, fd> dtl = dt_direct[l];
                    for (unsigned int k = 0; k < fd; ++k)
                      {
                        dxm[l] += dxi[l][k] * m.tangents[k];
                        for (unsigned int a = 0; a < fd; ++a)
                          dtl[a] += dxi[l][k] * dt[a][k];
                      }
                    dn[l] = normal_change<dim>(n, m.tangents, dtl);
                  }
              }
            else
              {
                // An obstacle: its closest point and normal as functions
                // of the slave point, by central differences.
                std::sort(touched.begin(), touched.end());
                touched.erase(std::unique(touched.begin(), touched.end()),
                              touched.end());
                const double                    h = 1e-6 * element_size;
                std::array<Tensor<1, dim>, dim> dx_dxs, dn_dxs;
                for (unsigned int c = 0; c < dim; ++c)
                  {
                    Point<dim> up = s.location, down = s.location;
                    up[c] += h;
                    down[c] -= h;
                    const auto pu = master.master.closest_point(up, nullptr);
                    const auto pd = master.master.closest_point(down, nullptr);
                    dx_dxs[c]     = (pu.location - pd.location) / (2. * h);
                    dn_dxs[c]     = (pu.normal - pd.normal) / (2. * h);
                  }
                for (const unsigned int l : touched)
                  for (unsigned int c = 0; c < dim; ++c)
                    {
                      dxm[l] += dxs[l][c] * dx_dxs[c];
                      dn[l] += dxs[l][c] * dn_dxs[c];
                    }
              }
            Eigen::VectorXd dg = Eigen::VectorXd::Zero(n_loc);
            for (const unsigned int l : touched)
              dg(l) = (dxs[l] - dxm[l]) * n + r * dn[l];

            // The slave functions' values here, and psi_j's with their
            // derivatives where the dual basis weights.
            Eigen::VectorXd N = Eigen::VectorXd::Zero(n_f);
            for (unsigned int a = 0; a < s.op.weights.size(); ++a)
              if (s.op.weights[a] != 0.)
                N(slave_fn.at(s.op.dofs[a][0])) = s.op.weights[a];
            Eigen::VectorXd psi;
            Eigen::MatrixXd d_psi;
            if (dual_basis)
              {
                psi                    = Eigen::VectorXd::Zero(n_f);
                psi.head(local.size()) = dual * N.head(local.size());
                d_psi                  = Eigen::MatrixXd::Zero(n_f, n_loc);
                for (unsigned int l = 0; l < n_slave; ++l)
                  d_psi.col(l).head(local.size()) =
                    d_dual[l] * N.head(local.size());
              }
            std::vector<std::pair<unsigned int, double>> master_values;
            for (unsigned int b = 0; b < m.op.weights.size(); ++b)
              if (m.op.weights[b] != 0.)
                master_values.emplace_back(b, m.op.weights[b]);

            for (unsigned int f = 0; f < n_f; ++f)
              {
                // N_j weights areas, normals and locations; the gap and
                // the operators take psi_j where the dual basis weights.
                const double          w_n  = N(f) * dA_value;
                const Eigen::VectorXd dw_n = N(f) * dA;
                const double w_d = dual_basis ? psi(f) * dA_value : w_n;
                const Eigen::VectorXd dw_d =
                  dual_basis ?
                    Eigen::VectorXd(d_psi.row(f).transpose() * dA_value +
                                    psi(f) * dA) :
                    dw_n;
                if (w_n == 0. && w_d == 0.)
                  continue;
                d_area[f] += dw_n;
                d_gap[f] += g * dw_d + w_d * dg;
                for (unsigned int c = 0; c < dim; ++c)
                  {
                    d_normal[f].row(c) += n[c] * dw_n.transpose();
                    for (const unsigned int l : touched)
                      d_normal[f](c, l) += w_n * dn[l][c];
                  }
                for (unsigned int k = 0; k < n_f; ++k)
                  if (N(k) != 0.)
                    d_op1[f].row(k) += N(k) * dw_d.transpose();
                for (const auto &[b, R] : master_values)
                  {
                    const unsigned int row = master_fn.at(m.op.dofs[b][0]);
                    d_op2[f].row(row) += R * dw_d.transpose();
                    for (const unsigned int l : touched)
                      {
                        double v = 0.;
                        for (unsigned int k = 0; k < fd; ++k)
                          v += dR[b][k] * dxi[l][k];
                        d_op2[f](row, l) += w_d * v;
                      }
                  }
              }
          }

        // Into each function's integrals, by unknown.
        std::vector<types::global_dof_index> slave_keys(n_f), master_keys(n_b);
        for (const auto &[key, f] : slave_fn)
          slave_keys[f] = key;
        for (const auto &[key, b] : master_fn)
          master_keys[b] = key;
        const auto scatter = [&](const auto &row, auto &to) {
          for (unsigned int l = 0; l < n_loc; ++l)
            if (row(l) != 0.)
              to[unknowns[l]] += row(l);
        };
        for (unsigned int f = 0; f < n_f; ++f)
          {
            if (d_area[f].isZero(0.) && d_gap[f].isZero(0.))
              continue;
            IntegralDerivatives<dim> &to = derivatives[slave_keys[f]];
            scatter(d_area[f], to.area);
            scatter(d_gap[f], to.gap);
            for (unsigned int c = 0; c < dim; ++c)
              scatter(d_normal[f].row(c), to.normal[c]);
            for (unsigned int k = 0; k < n_f; ++k)
              if (!d_op1[f].row(k).isZero(0.))
                scatter(d_op1[f].row(k), to.op1[slave_keys[k]]);
            for (unsigned int b = 0; b < n_b; ++b)
              if (!d_op2[f].row(b).isZero(0.))
                scatter(d_op2[f].row(b), to.op2[master_keys[b]]);
          }
      }



      template <int dim>
      PairDerivatives<dim>
      pair_derivatives(const double                                     area,
                       const double                                     gap,
                       const Tensor<1, dim>                            &normal,
                       const std::map<types::global_dof_index, double> &op1,
                       const std::map<types::global_dof_index, double> &op2,
                       const IntegralDerivatives<dim> &derivatives)
      {
        using Map = typename IntegralDerivatives<dim>::Map;
        PairDerivatives<dim> result;
        // d (X / A) = (dX - (X / A) dA) / A.
        const auto quotient = [&](const Map *dX, const double ratio) {
          Map sum;
          if (dX != nullptr)
            for (const auto &[u, v] : *dX)
              sum[u] += v / area;
          for (const auto &[u, v] : derivatives.area)
            sum[u] -= ratio * v / area;
          typename PairDerivatives<dim>::Gradient gradient(sum.begin(),
                                                           sum.end());
          return gradient;
        };
        result.gap = quotient(&derivatives.gap, gap / area);
        // d (v / |v|) = (I - n n) dv / |v|.
        const double         length = normal.norm();
        const Tensor<1, dim> n      = normal / length;
        Map                  dn[dim];
        for (unsigned int c = 0; c < dim; ++c)
          for (const auto &[u, v] : derivatives.normal[c])
            for (unsigned int e = 0; e < dim; ++e)
              dn[e][u] += ((e == c ? 1. : 0.) - n[e] * n[c]) * v / length;
        for (unsigned int e = 0; e < dim; ++e)
          result.normal[e].assign(dn[e].begin(), dn[e].end());
        // The entries make_operator() keeps.
        const auto op_derivatives =
          [&](const std::map<types::global_dof_index, double> &row,
              const std::map<types::global_dof_index, Map>    &d_row) {
            std::vector<typename PairDerivatives<dim>::Gradient> list;
            for (const auto &[key, value] : row)
              if (std::abs(value / area) > 1e-14)
                {
                  const auto it = d_row.find(key);
                  list.push_back(
                    quotient(it != d_row.end() ? &it->second : nullptr,
                             value / area));
                }
            return list;
          };
        result.op1 = op_derivatives(op1, derivatives.op1);
        result.op2 = op_derivatives(op2, derivatives.op2);
        return result;
      }



      template struct IntegralDerivatives<2>;
      template struct IntegralDerivatives<3>;
      template void
      add_element_derivatives<2>(
        const discretization::Body<2> &,
        const types::boundary_id,
        const MasterSide<2> &,
        const Point<1> &,
        const Point<1> &,
        const std::vector<ElementSample<2>> &,
        const QGauss<1> &,
        const std::map<types::global_dof_index, unsigned int> &,
        const Eigen::MatrixXd &,
        std::map<types::global_dof_index, IntegralDerivatives<2>> &);
      template void
      add_element_derivatives<3>(
        const discretization::Body<3> &,
        const types::boundary_id,
        const MasterSide<3> &,
        const Point<2> &,
        const Point<2> &,
        const std::vector<ElementSample<3>> &,
        const QGauss<1> &,
        const std::map<types::global_dof_index, unsigned int> &,
        const Eigen::MatrixXd &,
        std::map<types::global_dof_index, IntegralDerivatives<3>> &);
      template PairDerivatives<2>
      pair_derivatives<2>(const double,
                          const double,
                          const Tensor<1, 2> &,
                          const std::map<types::global_dof_index, double> &,
                          const std::map<types::global_dof_index, double> &,
                          const IntegralDerivatives<2> &);
      template PairDerivatives<3>
      pair_derivatives<3>(const double,
                          const double,
                          const Tensor<1, 3> &,
                          const std::map<types::global_dof_index, double> &,
                          const std::map<types::global_dof_index, double> &,
                          const IntegralDerivatives<3> &);
    } // namespace internal
  }   // namespace contact
} // namespace igabde
