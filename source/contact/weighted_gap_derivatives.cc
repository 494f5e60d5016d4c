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
        using Unknown = std::pair<unsigned int, types::global_dof_index>;

        /// Adds @p factor times the derivative of the face point @p s's
        /// measure by the slave unknowns (numbered by @p index) to
        /// @p into: d|t| = t . dt / |t| (2D), d|t_0 x t_1| = dt_0 . (t_1 x
        /// n) + dt_1 . (n x t_0) (3D), dt_a = sum_k N_k,a dz_k.
        template <int dim>
        void
        add_measure_derivative(const discretization::FacePoint<dim>  &s,
                               const double                           factor,
                               const std::map<Unknown, unsigned int> &index,
                               Eigen::VectorXd                       &into)
        {
          std::array<Tensor<1, dim>, dim - 1> share;
          if constexpr (dim == 2)
            share[0] = s.tangents[0] / s.measure;
          else
            {
              const Tensor<1, dim> unit =
                cross_product_3d(s.tangents[0], s.tangents[1]) / s.measure;
              share[0] = cross_product_3d(s.tangents[1], unit);
              share[1] = cross_product_3d(unit, s.tangents[0]);
            }
          for (unsigned int k = 0; k < s.op.weights.size(); ++k)
            if (s.op.weights[k] != 0.)
              for (unsigned int c = 0; c < dim; ++c)
                {
                  double v = 0.;
                  for (unsigned int a = 0; a + 1 < dim; ++a)
                    v += s.gradients[k][a] * share[a][c];
                  into(index.at({0u, s.op.dofs[k][c]})) += factor * v;
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



        /// The slave unknowns' derivatives of the element's dual basis,
        /// dA = (dD - A dM) M^{-1}, one matrix per slave unknown (the
        /// first @p n_slave of @p index), with the functions without a
        /// share held as element_dual_basis() holds them.
        template <int dim>
        std::vector<Eigen::MatrixXd>
        dual_derivatives(const ElementDualBasis<dim>           &dual,
                         const std::map<Unknown, unsigned int> &index,
                         const unsigned int                     n_slave)
        {
          const unsigned int           n = dual.local.size();
          std::vector<Eigen::MatrixXd> dM(n_slave, Eigen::MatrixXd::Zero(n, n));
          std::vector<Eigen::VectorXd> dD(n_slave, Eigen::VectorXd::Zero(n));
          for (unsigned int q = 0; q < dual.points.size(); ++q)
            {
              const auto     &s = dual.points[q];
              Eigen::VectorXd N = Eigen::VectorXd::Zero(n);
              for (unsigned int a = 0; a < s.op.weights.size(); ++a)
                if (s.op.weights[a] != 0.)
                  N(dual.local.at(s.op.dofs[a][0])) = s.op.weights[a];
              Eigen::VectorXd d_measure = Eigen::VectorXd::Zero(index.size());
              add_measure_derivative<dim>(s, dual.weights[q], index, d_measure);
              for (unsigned int l = 0; l < n_slave; ++l)
                if (d_measure(l) != 0.)
                  {
                    dM[l] += d_measure(l) * N * N.transpose();
                    dD[l] += d_measure(l) * N;
                  }
            }
          std::vector<Eigen::MatrixXd> result(n_slave);
          for (unsigned int l = 0; l < n_slave; ++l)
            {
              for (unsigned int j = 0; j < n; ++j)
                if (dual.no_share[j])
                  {
                    dM[l].row(j).setZero();
                    dM[l].col(j).setZero();
                    dD[l](j) = 0.;
                  }
              result[l] =
                (Eigen::MatrixXd(dD[l].asDiagonal()) - dual.A * dM[l]) *
                dual.M_inverse;
            }
          return result;
        }



        /// The unknowns of one slave element's integrals (the slave's
        /// first: its functions' on the element, then the master's at the
        /// samples), and its slave and master functions by key.
        struct ElementUnknowns
        {
          std::map<Unknown, unsigned int>                 index;
          std::vector<Unknown>                            unknowns;
          unsigned int                                    n_slave = 0;
          std::map<types::global_dof_index, unsigned int> slave_fn, master_fn;

          unsigned int
          number(const Unknown &u)
          {
            const auto [it, added] = index.emplace(u, unknowns.size());
            if (added)
              unknowns.push_back(u);
            return it->second;
          }

          /// Numbers the functions of @p op that do not vanish, into
          /// @p functions, and their unknowns as body @p body's.
          template <int dim>
          void
          add(const discretization::PointOperator<dim>        &op,
              const unsigned int                               body,
              std::map<types::global_dof_index, unsigned int> &functions)
          {
            for (unsigned int a = 0; a < op.weights.size(); ++a)
              if (op.weights[a] != 0.)
                {
                  functions.emplace(op.dofs[a][0], functions.size());
                  for (unsigned int c = 0; c < dim; ++c)
                    number({body, op.dofs[a][c]});
                }
          }
        };



        /// The derivatives at one sample by the element's unknowns (those
        /// of @p touched alone are not zero): the slave and master
        /// locations, the master normal, the closest point's face
        /// coordinates, and the slave measure (times the weight).
        template <int dim>
        struct SampleDerivatives
        {
          std::vector<Tensor<1, dim>>     dxs, dxm, dn;
          std::vector<Tensor<1, dim - 1>> dxi;
          Eigen::VectorXd                 d_measure;
          std::vector<unsigned int>       touched;

          explicit SampleDerivatives(const unsigned int n)
            : dxs(n)
            , dxm(n)
            , dn(n)
            , dxi(n)
            , d_measure(Eigen::VectorXd::Zero(n))
          {}

          void
          sort_touched()
          {
            std::sort(touched.begin(), touched.end());
            touched.erase(std::unique(touched.begin(), touched.end()),
                          touched.end());
          }
        };



        /// The closest point's motion on a deformable master (see the head
        /// of this file), into @p d.
        template <int dim>
        void
        add_deformable_master(const ElementSample<dim>              &sample,
                              const MasterSide<dim>                 &master,
                              const std::map<Unknown, unsigned int> &index,
                              SampleDerivatives<dim>                &d)
        {
          constexpr unsigned int fd = dim - 1;
          const auto            &s  = sample.s;
          const auto            &m  = sample.m;
          const Tensor<1, dim>   r  = s.location - m.location;
          // The coordinates the projection holds on the face's bounds.
          const auto          &grid = master.projectors[sample.part]->grid;
          std::array<bool, fd> held;
          for (unsigned int k = 0; k < fd; ++k)
            {
              const double lower = grid.breaks[k].front();
              const double upper = grid.breaks[k].back();
              const double tol   = 1e-12 * (upper - lower);
              held[k] =
                sample.xi[k] <= lower + tol || sample.xi[k] >= upper - tol;
            }
          const discretization::FaceSecondDerivatives<dim> dt =
            master.parts[sample.part]->face_second_derivatives(sample.xi);
          // H = T^T T - r . t_a,b, symmetric, on the free coordinates;
          // where the curvature term makes it indefinite (far from the
          // master), the projection's own Gauss-Newton matrix.
          Tensor<2, fd> H;
          for (unsigned int a = 0; a < fd; ++a)
            for (unsigned int b = 0; b < fd; ++b)
              H[a][b] = m.tangents[a] * m.tangents[b] - r * dt[a][b];
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
          // The right-hand side of H dxi per unknown, and the unknowns'
          // direct shares in dx_m and dt.
          const unsigned int                          n = d.dxs.size();
          std::vector<std::array<Tensor<1, dim>, fd>> dt_direct(n);
          std::vector<Tensor<1, fd>>                  rhs(n);
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
                  d.touched.push_back(l);
                  d.dxm[l][c] += m.op.weights[b];
                  for (unsigned int k = 0; k < fd; ++k)
                    {
                      rhs[l][k] += -m.op.weights[b] * m.tangents[k][c] +
                                   m.gradients[b][k] * r[c];
                      dt_direct[l][k][c] += m.gradients[b][k];
                    }
                }
          d.sort_touched();
          for (const unsigned int l : d.touched)
            {
              Tensor<1, fd> b = rhs[l];
              for (unsigned int k = 0; k < fd; ++k)
                if (held[k])
                  b[k] = 0.;
              d.dxi[l]                           = H_inverse * b;
              std::array<Tensor<1, dim>, fd> dtl = dt_direct[l];
              for (unsigned int k = 0; k < fd; ++k)
                {
                  d.dxm[l] += d.dxi[l][k] * m.tangents[k];
                  for (unsigned int a = 0; a < fd; ++a)
                    dtl[a] += d.dxi[l][k] * dt[a][k];
                }
              d.dn[l] = normal_change<dim>(m.normal, m.tangents, dtl);
            }
        }



        /// An obstacle's closest point and normal as functions of the slave
        /// point, by central differences of steps @p h, into @p d.
        template <int dim>
        void
        add_obstacle(const ElementSample<dim> &sample,
                     const MasterSide<dim>    &master,
                     const double              h,
                     SampleDerivatives<dim>   &d)
        {
          std::array<Tensor<1, dim>, dim> dx_dxs, dn_dxs;
          for (unsigned int c = 0; c < dim; ++c)
            {
              Point<dim> up = sample.s.location, down = sample.s.location;
              up[c] += h;
              down[c] -= h;
              const auto pu = master.master.closest_point(up, nullptr);
              const auto pd = master.master.closest_point(down, nullptr);
              dx_dxs[c]     = (pu.location - pd.location) / (2. * h);
              dn_dxs[c]     = (pu.normal - pd.normal) / (2. * h);
            }
          d.sort_touched();
          for (const unsigned int l : d.touched)
            for (unsigned int c = 0; c < dim; ++c)
              {
                d.dxm[l] += d.dxs[l][c] * dx_dxs[c];
                d.dn[l] += d.dxs[l][c] * dn_dxs[c];
              }
        }



        /// The derivatives of one slave element's integrals, per slave
        /// function f, each row a vector over the element's unknowns.
        struct ElementRows
        {
          std::vector<Eigen::VectorXd> area, gap;
          std::vector<Eigen::MatrixXd> normal, op1, op2;

          ElementRows(const unsigned int dim,
                      const unsigned int n_f,
                      const unsigned int n_b,
                      const unsigned int n)
            : area(n_f, Eigen::VectorXd::Zero(n))
            , gap(n_f, Eigen::VectorXd::Zero(n))
            , normal(n_f, Eigen::MatrixXd::Zero(dim, n))
            , op1(n_f, Eigen::MatrixXd::Zero(n_f, n))
            , op2(n_f, Eigen::MatrixXd::Zero(n_b, n))
          {}
        };
      } // namespace



      template <int dim>
      ElementDualBasis<dim>
      element_dual_basis(const discretization::Body<dim> &slave_body,
                         const types::boundary_id         slave_face,
                         const Point<dim - 1>            &lo,
                         const Point<dim - 1>            &hi,
                         const QGauss<1>                 &rule)
      {
        constexpr unsigned int fd = dim - 1;
        ElementDualBasis<dim>  dual;
        unsigned int           nq = 1;
        for (unsigned int k = 0; k < fd; ++k)
          nq *= rule.size();
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
            dual.points.push_back(slave_body.face_point(slave_face, eta));
            dual.weights.push_back(weight);
            const auto &op = dual.points.back().op;
            for (unsigned int a = 0; a < op.weights.size(); ++a)
              if (op.weights[a] != 0.)
                dual.local.emplace(op.dofs[a][0], dual.local.size());
          }
        const unsigned int n            = dual.local.size();
        Eigen::MatrixXd    M            = Eigen::MatrixXd::Zero(n, n);
        Eigen::VectorXd    D            = Eigen::VectorXd::Zero(n);
        double             element_area = 0.;
        for (unsigned int q = 0; q < nq; ++q)
          {
            const auto  &s  = dual.points[q];
            const double dA = dual.weights[q] * s.measure;
            element_area += dA;
            Eigen::VectorXd N = Eigen::VectorXd::Zero(n);
            for (unsigned int a = 0; a < s.op.weights.size(); ++a)
              if (s.op.weights[a] != 0.)
                N(dual.local.at(s.op.dofs[a][0])) = s.op.weights[a];
            M += dA * N * N.transpose();
            D += dA * N;
          }
        dual.no_share.assign(n, false);
        for (unsigned int j = 0; j < n; ++j)
          if (D(j) <= 1e-12 * element_area)
            {
              dual.no_share[j] = true;
              M.row(j).setZero();
              M.col(j).setZero();
              M(j, j) = 1.;
              D(j)    = 0.;
            }
        dual.M_inverse = M.inverse();
        dual.A         = D.asDiagonal() * dual.M_inverse;
        return dual;
      }



      template <int dim>
      void
      add_element_derivatives(const MasterSide<dim>                 &master,
                              const std::vector<ElementSample<dim>> &samples,
                              const ElementDualBasis<dim>           *dual,
                              std::map<types::global_dof_index,
                                       IntegralDerivatives<dim>> &derivatives)
      {
        if (samples.empty())
          return;
        const bool deformable = !master.projectors.empty();

        // The element's unknowns: the slave's (the dual basis's functions
        // first, in its numbering), then the master's.
        ElementUnknowns e;
        if (dual != nullptr)
          for (const auto &point : dual->points)
            e.add<dim>(point.op, 0u, e.slave_fn);
        for (const auto &sample : samples)
          e.add<dim>(sample.s.op, 0u, e.slave_fn);
        e.n_slave = e.unknowns.size();
        for (const auto &sample : samples)
          e.add<dim>(sample.m.op, 1u, e.master_fn);
        const unsigned int n_loc = e.unknowns.size();
        const unsigned int n_f   = e.slave_fn.size();
        const unsigned int n_b   = e.master_fn.size();
        const unsigned int n_d   = dual != nullptr ? dual->local.size() : 0;
        Assert(dual == nullptr ||
                 std::all_of(dual->local.begin(),
                             dual->local.end(),
                             [&](const auto &entry) {
                               return e.slave_fn.at(entry.first) ==
                                      entry.second;
                             }),
               ExcInternalError());

        const std::vector<Eigen::MatrixXd> d_dual =
          dual != nullptr ? dual_derivatives<dim>(*dual, e.index, e.n_slave) :
                            std::vector<Eigen::MatrixXd>();

        // An obstacle's differences: a millionth of the size of the part
        // of the element that the samples integrate.
        double area = 0.;
        for (const auto &sample : samples)
          area += sample.weight * sample.s.measure;
        const double element_size = std::pow(area, 1. / (dim - 1));
        ElementRows  rows(dim, n_f, n_b, n_loc);
        for (const auto &sample : samples)
          {
            const auto          &s        = sample.s;
            const auto          &m        = sample.m;
            const double         dA_value = sample.weight * s.measure;
            const Tensor<1, dim> r        = s.location - m.location;
            const Tensor<1, dim> n        = m.normal;
            const double         g        = r * n;

            SampleDerivatives<dim> d(n_loc);
            add_measure_derivative<dim>(s, sample.weight, e.index, d.d_measure);
            for (unsigned int a = 0; a < s.op.weights.size(); ++a)
              if (s.op.weights[a] != 0.)
                for (unsigned int c = 0; c < dim; ++c)
                  {
                    const unsigned int l = e.index.at({0u, s.op.dofs[a][c]});
                    d.touched.push_back(l);
                    d.dxs[l][c] += s.op.weights[a];
                  }
            if (deformable)
              add_deformable_master<dim>(sample, master, e.index, d);
            else
              add_obstacle<dim>(sample, master, 1e-6 * element_size, d);
            Eigen::VectorXd dg = Eigen::VectorXd::Zero(n_loc);
            for (const unsigned int l : d.touched)
              dg(l) = (d.dxs[l] - d.dxm[l]) * n + r * d.dn[l];

            // The slave functions' values here, and psi_j's with their
            // derivatives where the dual basis weights.
            Eigen::VectorXd N = Eigen::VectorXd::Zero(n_f);
            for (unsigned int a = 0; a < s.op.weights.size(); ++a)
              if (s.op.weights[a] != 0.)
                N(e.slave_fn.at(s.op.dofs[a][0])) = s.op.weights[a];
            Eigen::VectorXd psi;
            Eigen::MatrixXd d_psi;
            if (dual != nullptr)
              {
                psi           = Eigen::VectorXd::Zero(n_f);
                psi.head(n_d) = dual->A * N.head(n_d);
                d_psi         = Eigen::MatrixXd::Zero(n_f, n_loc);
                for (unsigned int l = 0; l < e.n_slave; ++l)
                  d_psi.col(l).head(n_d) = d_dual[l] * N.head(n_d);
              }

            for (unsigned int f = 0; f < n_f; ++f)
              {
                // N_j weights areas, normals and locations; the gap and
                // the operators take psi_j where the dual basis weights.
                const double          w_n  = N(f) * dA_value;
                const Eigen::VectorXd dw_n = N(f) * d.d_measure;
                const double w_d = dual != nullptr ? psi(f) * dA_value : w_n;
                const Eigen::VectorXd dw_d =
                  dual != nullptr ?
                    Eigen::VectorXd(d_psi.row(f).transpose() * dA_value +
                                    psi(f) * d.d_measure) :
                    dw_n;
                if (w_n == 0. && w_d == 0.)
                  continue;
                rows.area[f] += dw_n;
                rows.gap[f] += g * dw_d + w_d * dg;
                for (unsigned int c = 0; c < dim; ++c)
                  {
                    rows.normal[f].row(c) += n[c] * dw_n.transpose();
                    for (const unsigned int l : d.touched)
                      rows.normal[f](c, l) += w_n * d.dn[l][c];
                  }
                for (unsigned int k = 0; k < n_f; ++k)
                  if (N(k) != 0.)
                    rows.op1[f].row(k) += N(k) * dw_d.transpose();
                for (unsigned int b = 0; b < m.op.weights.size(); ++b)
                  {
                    if (m.op.weights[b] == 0.)
                      continue;
                    const unsigned int row = e.master_fn.at(m.op.dofs[b][0]);
                    rows.op2[f].row(row) += m.op.weights[b] * dw_d.transpose();
                    if (deformable)
                      for (const unsigned int l : d.touched)
                        {
                          double v = 0.;
                          for (unsigned int k = 0; k + 1 < dim; ++k)
                            v += m.gradients[b][k] * d.dxi[l][k];
                          rows.op2[f](row, l) += w_d * v;
                        }
                  }
              }
          }

        // Into each function's integrals, by unknown.
        std::vector<types::global_dof_index> slave_keys(n_f), master_keys(n_b);
        for (const auto &[key, f] : e.slave_fn)
          slave_keys[f] = key;
        for (const auto &[key, b] : e.master_fn)
          master_keys[b] = key;
        const auto scatter = [&](const auto &row, auto &to) {
          for (unsigned int l = 0; l < n_loc; ++l)
            if (row(l) != 0.)
              to[e.unknowns[l]] += row(l);
        };
        for (unsigned int f = 0; f < n_f; ++f)
          {
            if (rows.area[f].isZero(0.) && rows.gap[f].isZero(0.))
              continue;
            IntegralDerivatives<dim> &to = derivatives[slave_keys[f]];
            scatter(rows.area[f], to.area);
            scatter(rows.gap[f], to.gap);
            for (unsigned int c = 0; c < dim; ++c)
              scatter(rows.normal[f].row(c), to.normal[c]);
            for (unsigned int k = 0; k < n_f; ++k)
              if (!rows.op1[f].row(k).isZero(0.))
                scatter(rows.op1[f].row(k), to.op1[slave_keys[k]]);
            for (unsigned int b = 0; b < n_b; ++b)
              if (!rows.op2[f].row(b).isZero(0.))
                scatter(rows.op2[f].row(b), to.op2[master_keys[b]]);
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
      template ElementDualBasis<2>
      element_dual_basis<2>(const discretization::Body<2> &,
                            const types::boundary_id,
                            const Point<1> &,
                            const Point<1> &,
                            const QGauss<1> &);
      template ElementDualBasis<3>
      element_dual_basis<3>(const discretization::Body<3> &,
                            const types::boundary_id,
                            const Point<2> &,
                            const Point<2> &,
                            const QGauss<1> &);
      template void
      add_element_derivatives<2>(
        const MasterSide<2> &,
        const std::vector<ElementSample<2>> &,
        const ElementDualBasis<2> *,
        std::map<types::global_dof_index, IntegralDerivatives<2>> &);
      template void
      add_element_derivatives<3>(
        const MasterSide<3> &,
        const std::vector<ElementSample<3>> &,
        const ElementDualBasis<3> *,
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
