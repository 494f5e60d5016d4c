#include <igabde/base/utilities.h>

#include <igabde/discretization/body_description.h>

#include <igabde/contact/condition_check.h>
#include <igabde/contact/contact_stage.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace igabde
{
  namespace contact
  {
    namespace
    {
      /// Rows n, a[, b]: an orthonormal frame with n first.
      template <int dim>
      Tensor<2, dim>
      local_frame(const Tensor<1, dim> &n)
      {
        Tensor<2, dim> T;
        T[0] = n;
        if (dim == 2)
          {
            T[1][0] = -n[1];
            T[1][1] = n[0];
          }
        else
          {
            // First tangent: the axis least aligned with n, made orthogonal.
            unsigned int axis = 0;
            for (unsigned int d = 1; d < dim; ++d)
              if (std::abs(n[d]) < std::abs(n[axis]))
                axis = d;
            Tensor<1, dim> e;
            e[axis]          = 1.;
            Tensor<1, dim> a = e - (e * n) * n;
            a /= a.norm();
            T[1] = a;
            Tensor<1, dim> b;
            b[0] = n[1] * a[2] - n[2] * a[1];
            b[1] = n[2] * a[0] - n[0] * a[2];
            b[2] = n[0] * a[1] - n[1] * a[0];
            T[2] = b;
          }
        return T;
      }
    } // namespace



    template <int dim>
    ContactStage<dim>::ContactStage(
      const ContactSettings<dim>                                    &settings,
      const std::vector<std::unique_ptr<discretization::Body<dim>>> &bodies,
      std::ostream                                                  &log)
      : settings(settings)
      , bodies(bodies)
      , log(log)
    {
      AssertThrow(settings.rigid_plane || bodies.size() == 2,
                  base::ExcInput(settings.scene_file +
                                 ": contact needs Body 2 (deformable) or a "
                                 "rigid plane."));
    }



    template <int dim>
    const std::vector<PointPair<dim>> &
    ContactStage<dim>::pairs() const
    {
      return pair_list;
    }



    template <int dim>
    typename ContactStage<dim>::State
    ContactStage<dim>::save_state() const
    {
      return {p, alpha, u_rel, previous_external, status, has_previous};
    }



    template <int dim>
    void
    ContactStage<dim>::restore_state(const State &state)
    {
      p                 = state.p;
      alpha             = state.alpha;
      u_rel             = state.u_rel;
      previous_external = state.previous_external;
      status            = state.status;
      has_previous      = state.has_previous;
    }



    template <int dim>
    const ContactProblem &
    ContactStage<dim>::condensed_problem() const
    {
      return problem;
    }



    template <int dim>
    double
    ContactStage<dim>::flexibility_asymmetry() const
    {
      return asymmetry;
    }



    template <int dim>
    const Eigen::VectorXd &
    ContactStage<dim>::forces() const
    {
      return p;
    }



    template <int dim>
    void
    ContactStage<dim>::form_pairs()
    {
      const auto &body1 = *bodies[0];
      const auto  slave = body1.surface_points(settings.slave_face);
      AssertThrow(!slave.empty(),
                  base::ExcInput(settings.scene_file + ": Contact/Slave face " +
                                 std::to_string(settings.slave_face) +
                                 " of Body 1 has no contact points."));

      double size = 0.;
      for (const auto &s : slave)
        size = std::max(size, (s.location - slave[0].location).norm());
      size = std::max(size, 1e-300);

      std::vector<discretization::SurfacePoint<dim>> master;
      if (!settings.rigid_plane)
        master = bodies[1]->surface_points(settings.master_face);

      pair_list.clear();
      for (const auto &s : slave)
        {
          PointPair<dim> pair;
          pair.x1   = s.location;
          pair.op1  = s.op;
          pair.area = s.tributary_area;
          Tensor<1, dim> n;
          if (settings.rigid_plane)
            {
              n = settings.plane_normal;
              pair.x2 =
                s.location - ((s.location - settings.plane_point) * n) * n;
            }
          else
            {
              // The coincident master point where the surfaces match, else
              // the closest point of the master face (exact on NURBS).
              unsigned int best = 0;
              for (unsigned int m = 1; m < master.size(); ++m)
                if ((master[m].location - s.location).norm() <
                    (master[best].location - s.location).norm())
                  best = m;
              if ((master[best].location - s.location).norm() <= 1e-8 * size)
                {
                  n        = master[best].normal;
                  pair.x2  = master[best].location;
                  pair.op2 = master[best].op;
                }
              else
                {
                  const auto m =
                    bodies[1]->closest_surface_point(settings.master_face,
                                                     s.location,
                                                     master[best]);
                  n        = m.normal;
                  pair.x2  = m.location;
                  pair.op2 = m.op;
                }
            }
          AssertThrow(
            s.normal * n < 0.,
            base::ExcInput(
              settings.scene_file +
              ": the contact surfaces do not "
              "face each other at (" +
              [&] {
                std::ostringstream o;
                o << s.location;
                return o.str();
              }() +
              "): the outward normal of Body 1's face " +
              std::to_string(settings.slave_face) + " points away from " +
              (settings.rigid_plane ?
                 std::string("the rigid plane (check Body 2/Plane "
                             "normal: it must point towards Body "
                             "1)") :
                 "Body 2's face " + std::to_string(settings.master_face)) +
              "; check Contact/Slave face and Contact/Master "
              "face."));
          pair.frame = local_frame<dim>(n);
          pair.gap   = (pair.x1 - pair.x2) * n;
          AssertThrow(pair.gap >= -1e-10 * size,
                      base::ExcInput(settings.scene_file +
                                     ": Body 1 initially penetrates Body 2 "
                                     "(gap " +
                                     std::to_string(pair.gap) +
                                     "); move the bodies apart."));
          pair.gap = std::max(pair.gap, 0.);
          pair_list.push_back(pair);
        }
    }



    template <int dim>
    void
    ContactStage<dim>::form_flexibility()
    {
      // Unit force pairs along the local directions that carry unknowns:
      // +T_j[s] on Body 1 at x1_j, -T_j[s] on Body 2 at x2_j, so that
      // F^L = T^T F^G T comes out directly (the signs cancel in each body's
      // share) and a frictionless scene needs only the normal directions.
      // Each body gives its share from its Schur complement on the contact
      // face, or by one solve per column.
      const unsigned int nc = pair_list.size();
      const unsigned int m  = n_components;
      Eigen::MatrixXd    FL(m * nc, m * nc);
      FL.setZero();
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          std::vector<discretization::PointOperator<dim>> ops;
          std::vector<Tensor<1, dim>>                     directions;
          ops.reserve(m * nc);
          directions.reserve(m * nc);
          for (unsigned int j = 0; j < nc; ++j)
            for (unsigned int s = 0; s < m; ++s)
              {
                ops.push_back(b == 0 ? pair_list[j].op1 : pair_list[j].op2);
                directions.push_back(pair_list[j].frame[s]);
              }
          const FullMatrix<double> Fb = bodies[b]->flexibility(ops, directions);
          for (unsigned int i = 0; i < m * nc; ++i)
            for (unsigned int j = 0; j < m * nc; ++j)
              FL(i, j) += Fb(i, j);
          if (settings.progress)
            log << "  contact: " << bodies[b]->description().name
                << " condensed onto " << m * nc << " pair directions"
                << (bodies[b]->has_schur_complement() ?
                      " (Schur complement on " +
                        std::to_string(bodies[b]->n_interface_dofs()) +
                        " face unknowns)" :
                      " (one solve per column)")
                << std::endl;
        }

      // Rigid modes left free by the supports: u = K^+ f + R alpha, with the
      // equilibrium R^T (f_ext + f_contact) = 0 joining the BDE system.
      alpha_modes.clear();
      for (unsigned int b = 0; b < bodies.size(); ++b)
        for (unsigned int k = 0; k < bodies[b]->free_rigid_modes().size(); ++k)
          alpha_modes.emplace_back(b, k);
      Eigen::MatrixXd GL(m * nc, alpha_modes.size());
      rigid_mode_loads.resize(alpha_modes.size());
      for (unsigned int a = 0; a < alpha_modes.size(); ++a)
        {
          const auto [b, k]   = alpha_modes[a];
          const auto  &mode   = bodies[b]->free_rigid_modes()[k];
          const double sign   = (b == 0 ? 1. : -1.);
          rigid_mode_loads(a) = mode * bodies[b]->load_vector();
          for (unsigned int i = 0; i < nc; ++i)
            {
              const Tensor<1, dim> r =
                (b == 0 ? pair_list[i].op1 : pair_list[i].op2)
                  .displacement(mode);
              for (unsigned int s = 0; s < m; ++s)
                GL(m * i + s, a) = sign * (pair_list[i].frame[s] * r);
            }
          log << "  " << bodies[b]->description().name << ": free rigid mode '"
              << bodies[b]->free_rigid_mode_names()[k]
              << "' closed by the contact equilibrium (exact, no springs)"
              << std::endl;
        }

      // Pairs whose two points are both held by supports carry no
      // information: their flexibility rows and rigid-mode rows vanish.
      // Leave them out (a pinned point of a floating body keeps its rigid
      // motion, so it stays).
      double max_diag = 0., max_g = 0.;
      for (unsigned int i = 0; i < m * nc; ++i)
        max_diag = std::max(max_diag, FL(i, i));
      if (GL.size() > 0)
        max_g = GL.cwiseAbs().maxCoeff();
      std::vector<unsigned int> keep;
      for (unsigned int i = 0; i < nc; ++i)
        {
          const double g_row =
            (GL.cols() > 0 ? GL.row(m * i).cwiseAbs().maxCoeff() : 0.);
          if (FL(m * i, m * i) > 1e-12 * max_diag || g_row > 1e-12 * max_g)
            keep.push_back(i);
        }
      n_dropped = nc - keep.size();
      AssertThrow(!keep.empty(),
                  base::ExcInput(settings.scene_file +
                                 ": every contact pair is held by supports on "
                                 "both sides; nothing can touch."));
      std::vector<PointPair<dim>> kept_pairs;
      Eigen::MatrixXd             W(m * keep.size(), m * keep.size());
      problem.G.resize(m * keep.size(), alpha_modes.size());
      for (unsigned int i = 0; i < keep.size(); ++i)
        {
          kept_pairs.push_back(pair_list[keep[i]]);
          for (unsigned int j = 0; j < keep.size(); ++j)
            W.block(m * i, m * j, m, m) =
              FL.block(m * keep[i], m * keep[j], m, m);
          problem.G.middleRows(m * i, m) = GL.middleRows(m * keep[i], m);
        }
      pair_list = kept_pairs;
      asymmetry = (W - W.transpose()).norm() / std::max(W.norm(), 1e-300);
      W         = 0.5 * (W + W.transpose());

      problem.n_contacts   = pair_list.size();
      problem.n_components = m;
      problem.W            = W;
      problem.q            = Eigen::VectorXd::Zero(m * pair_list.size());
      problem.mu.assign(pair_list.size(), settings.friction_coefficient);
      problem.name = settings.scene_file;

      problem.b.resize(alpha_modes.size());
      problem.b.setZero();
      problem.check_consistency();

      log << "  contact: " << pair_list.size() << " pairs ("
          << (settings.rigid_plane ? "rigid plane" : "two bodies") << ", "
          << m * pair_list.size() << " contact unknowns"
          << (m == 1 ? ", frictionless: no tangential unknowns" : "") << ")"
          << std::endl;
      if (n_dropped > 0)
        log << "  contact: left out " << n_dropped
            << " pairs whose two points are both held by supports (zero "
               "flexibility, no information)"
            << std::endl;
      if (asymmetry > 1e-8)
        log << "  contact: warning: flexibility asymmetry " << asymmetry
            << std::endl;
    }



    template <int dim>
    void
    ContactStage<dim>::build_pairs(TimerOutput &timer)
    {
      n_components = (settings.friction_coefficient > 0. ? dim : 1);
      TimerOutput::Scope t(timer, "contact: pairs");
      form_pairs();
    }



    template <int dim>
    std::vector<discretization::PointOperator<dim>>
    ContactStage<dim>::contact_operators(const unsigned int b) const
    {
      std::vector<discretization::PointOperator<dim>> ops;
      for (const auto &pair : pair_list)
        ops.push_back(b == 0 ? pair.op1 : pair.op2);
      return ops;
    }



    template <int dim>
    void
    ContactStage<dim>::condense(TimerOutput &timer)
    {
      {
        TimerOutput::Scope t(timer, "contact: condensation");
        form_flexibility();
      }
      p                 = Eigen::VectorXd::Zero(problem.n_rows());
      alpha             = Eigen::VectorXd::Zero(problem.n_alpha());
      previous_external = Eigen::VectorXd::Zero(problem.n_rows());
    }



    template <int dim>
    Eigen::VectorXd
    ContactStage<dim>::relative_displacement(
      const std::vector<Vector<double>> &u) const
    {
      const unsigned int m = n_components;
      Eigen::VectorXd    result(m * pair_list.size());
      for (unsigned int i = 0; i < pair_list.size(); ++i)
        {
          Tensor<1, dim> du = pair_list[i].op1.displacement(u[0]);
          if (!settings.rigid_plane)
            du -= pair_list[i].op2.displacement(u[1]);
          for (unsigned int s = 0; s < m; ++s)
            result(m * i + s) = pair_list[i].frame[s] * du;
        }
      return result;
    }



    template <int dim>
    Tensor<1, dim>
    ContactStage<dim>::global_force(const unsigned int     i,
                                    const Eigen::VectorXd &forces) const
    {
      Tensor<1, dim> f;
      for (unsigned int s = 0; s < n_components; ++s)
        f += forces(n_components * i + s) * pair_list[i].frame[s];
      return f;
    }



    template <int dim>
    std::pair<Eigen::VectorXd, Eigen::VectorXd>
    ContactStage<dim>::initial_guess() const
    {
      // Candidate 1, first step: no force, rigid modes placed so that the
      // closest pair just touches (with every pair open the alpha columns of
      // the Newton matrix vanish). Later steps: the previous step's forces
      // and rigid-mode amplitudes (warm start).
      const unsigned int    m = n_components;
      const Eigen::VectorXd p0 =
        has_previous ? p : Eigen::VectorXd::Zero(problem.n_rows());
      const Eigen::VectorXd a0 = has_previous ? alpha :
                                 problem.n_alpha() > 0 ?
                                                touching_alpha(problem) :
                                                Eigen::VectorXd::Zero(0);

      // Candidate 2: a bilateral solve, W_cc p_c + G_c alpha = -q_c and
      // G_c^T p_c = b, over the pairs expected closed and sticking: in the
      // first step those that touch in the undeformed geometry, later those
      // closed at the end of the previous step. On flat matching surfaces
      // with zero gap every pair is at a tie of the min function, where the
      // first Newton matrix is a poor model, and after a load change the
      // warm start violates the equilibrium of floating bodies by the whole
      // change; this start is exact when the contact state does not change.
      // The better candidate by natural-map plus equilibrium residual is
      // used.
      std::vector<unsigned int> rows;
      double                    size = 0.;
      for (const auto &pair : pair_list)
        size = std::max(size, (pair.x1 - pair_list[0].x1).norm());
      // Directions held by supports on both sides (zero flexibility, no
      // rigid motion) carry no force and are left out of this start.
      const double max_diag = problem.W.diagonal().cwiseAbs().maxCoeff();
      const double max_g =
        (problem.G.size() > 0 ? problem.G.cwiseAbs().maxCoeff() : 0.);
      for (unsigned int i = 0; i < pair_list.size(); ++i)
        if (has_previous ? status[i] != ContactStatus::open :
                           pair_list[i].gap <= 1e-12 * std::max(size, 1e-300))
          for (unsigned int s = 0; s < m; ++s)
            {
              const unsigned int r = m * i + s;
              const double       g =
                (problem.G.cols() > 0 ? problem.G.row(r).cwiseAbs().maxCoeff() :
                                        0.);
              if (problem.W(r, r) > 1e-12 * max_diag || g > 1e-12 * max_g)
                rows.push_back(r);
            }
      if (rows.empty())
        return {p0, a0};
      const unsigned int nr = rows.size(), na = problem.n_alpha();
      Eigen::MatrixXd    A = Eigen::MatrixXd::Zero(nr + na, nr + na);
      Eigen::VectorXd    rhs(nr + na);
      for (unsigned int i = 0; i < nr; ++i)
        {
          for (unsigned int j = 0; j < nr; ++j)
            A(i, j) = problem.W(rows[i], rows[j]);
          for (unsigned int k = 0; k < na; ++k)
            {
              A(i, nr + k) = problem.G(rows[i], k);
              A(nr + k, i) = problem.G(rows[i], k);
            }
          rhs(i) = -problem.q(rows[i]);
        }
      for (unsigned int k = 0; k < na; ++k)
        rhs(nr + k) = problem.b(k);
      const Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
      if (!lu.isInvertible())
        return {p0, a0};
      const Eigen::VectorXd x = lu.solve(rhs);
      if (!x.allFinite())
        return {p0, a0};
      Eigen::VectorXd p1 = Eigen::VectorXd::Zero(problem.n_rows());
      for (unsigned int i = 0; i < nr; ++i)
        p1(rows[i]) = x(i);
      const Eigen::VectorXd a1 = x.tail(na);

      // Natural-map residual plus the equilibrium of floating bodies (the
      // natural map alone is zero for p = 0 with every pair open).
      const auto error = [&](const Eigen::VectorXd &pp,
                             const Eigen::VectorXd &aa) {
        double e =
          relative_natural_map_error(problem,
                                     pp,
                                     problem.relative_displacement(pp, aa));
        if (na > 0)
          e += (problem.G.transpose() * pp - problem.b).norm() /
               std::max(problem.b.norm(), 1e-300);
        return e;
      };
      if (error(p1, a1) < error(p0, a0))
        return {p1, a1};
      return {p0, a0};
    }



    template <int dim>
    void
    ContactStage<dim>::solve_step(const unsigned int           step,
                                  const double                 load_factor,
                                  std::vector<Vector<double>> &u,
                                  base::Json                  &record,
                                  TimerOutput                 &timer)
    {
      const unsigned int    m     = n_components;
      const Eigen::VectorXd U     = relative_displacement(u);
      const Eigen::VectorXd carry = problem.W * p + problem.G * alpha;

      // Normal rows: total relative displacement, gap included. Tangential
      // rows: increments of this step (friction is incremental).
      for (unsigned int i = 0; i < pair_list.size(); ++i)
        {
          problem.q(m * i) = pair_list[i].gap + U(m * i);
          for (unsigned int s = 1; s < m; ++s)
            problem.q(m * i + s) =
              U(m * i + s) - previous_external(m * i + s) - carry(m * i + s);
        }
      problem.b = -load_factor * rigid_mode_loads;

      BNewtonSolver::Result result;
      {
        TimerOutput::Scope t(timer, "contact: B-Newton");
        BNewtonSolver      solver(settings.solver);
        const auto [p0, alpha0] = initial_guess();
        result                  = solver.solve(problem, p0, alpha0);
      }
      log << "  B-Newton: " << result.summary() << std::endl;

      record["newton_iterations"] = result.iterations;
      record["residual"]          = result.residual;
      record["n_open"]            = result.n_open;
      record["n_stick"]           = result.n_stick;
      record["n_slip"]            = result.n_slip;

      AssertThrow(
        result.converged,
        ExcContactNotConverged(
          settings.scene_file + ": load step " + std::to_string(step) +
          ": the contact solver did not converge: " + result.diagnosis +
          ". Try more load steps (Load path/Number of steps) or step cuts "
          "(Contact/Max step cuts), a larger Contact/Max iterations, or "
          "check that the bodies are supported."));

      const ConditionReport report =
        check_contact_conditions(problem,
                                 result.p,
                                 result.u,
                                 settings.check_tolerance);
      double worst = 0.;
      for (const auto &c : report.conditions)
        worst = std::max(worst, c.max_violation);
      record["condition_check_max_violation"] = worst;
      AssertThrow(report.passed(),
                  base::ExcInput(settings.scene_file + ": load step " +
                                 std::to_string(step) +
                                 ": the contact solution violates a contact "
                                 "condition: " +
                                 report.first_violation()));

      p                 = result.p;
      alpha             = result.alpha;
      u_rel             = result.u;
      status            = result.status;
      previous_external = U;
      has_previous      = true;

      // Contact forces back to the fields.
      {
        TimerOutput::Scope          t(timer, "contact: fields");
        std::vector<Vector<double>> loads;
        for (const auto &body : bodies)
          loads.emplace_back(body->n_dofs());
        Tensor<1, dim> total;
        for (unsigned int i = 0; i < pair_list.size(); ++i)
          {
            const Tensor<1, dim> f = global_force(i, p);
            total += f;
            pair_list[i].op1.distribute(f, loads[0]);
            if (!settings.rigid_plane)
              pair_list[i].op2.distribute(-f, loads[1]);
          }
        for (unsigned int b = 0; b < bodies.size(); ++b)
          {
            std::vector<Vector<double>> column(1, loads[b]);
            bodies[b]->solve(column);
            u[b] += column[0];
          }
        for (unsigned int a = 0; a < alpha_modes.size(); ++a)
          {
            const auto [b, k] = alpha_modes[a];
            u[b].add(alpha(a), bodies[b]->free_rigid_modes()[k]);
          }
        base::Json force = base::Json::array();
        for (unsigned int c = 0; c < dim; ++c)
          force.push_back(total[c]);
        record["total_contact_force"] = force;
        log << "  total contact force on Body 1: " << std::setprecision(6)
            << total << std::endl;
      }
    }



    template <int dim>
    void
    ContactStage<dim>::write_step_output(const unsigned int step,
                                         const std::string &directory) const
    {
      if (status.empty())
        return;
      const unsigned int m = n_components;
      std::ostringstream stem;
      stem << directory << "/contact-" << std::setw(4) << std::setfill('0')
           << step;

      // CSV, full precision.
      std::ofstream csv(stem.str() + ".csv");
      csv << "pair";
      const char *xyz = "xyz";
      for (unsigned int d = 0; d < dim; ++d)
        csv << "," << xyz[d];
      csv << ",area,gap,p_n";
      for (unsigned int s = 1; s < m; ++s)
        csv << ",p_t" << s;
      csv << ",pressure";
      for (unsigned int s = 1; s < m; ++s)
        csv << ",slip_t" << s;
      csv << ",status\n" << std::setprecision(12);
      for (unsigned int i = 0; i < pair_list.size(); ++i)
        {
          csv << i;
          for (unsigned int d = 0; d < dim; ++d)
            csv << "," << pair_list[i].x1[d];
          csv << "," << pair_list[i].area << "," << u_rel(m * i);
          for (unsigned int s = 0; s < m; ++s)
            csv << "," << p(m * i + s);
          csv << "," << p(m * i) / pair_list[i].area;
          for (unsigned int s = 1; s < m; ++s)
            csv << "," << u_rel(m * i + s);
          csv << "," << to_string(status[i]) << "\n";
        }

      // VTU point cloud for ParaView.
      std::ofstream      vtu(stem.str() + ".vtu");
      const unsigned int n = pair_list.size();
      vtu
        << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" "
           "version=\"0.1\" byte_order=\"LittleEndian\">\n<UnstructuredGrid>\n"
        << "<Piece NumberOfPoints=\"" << n << "\" NumberOfCells=\"" << n
        << "\">\n<Points>\n<DataArray type=\"Float64\" "
           "NumberOfComponents=\"3\" format=\"ascii\">\n"
        << std::setprecision(12);
      for (const auto &pair : pair_list)
        {
          for (unsigned int d = 0; d < 3; ++d)
            vtu << (d < dim ? pair.x1[d] : 0.) << " ";
          vtu << "\n";
        }
      vtu << "</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int32\" "
             "Name=\"connectivity\" format=\"ascii\">\n";
      for (unsigned int i = 0; i < n; ++i)
        vtu << i << " ";
      vtu << "\n</DataArray>\n<DataArray type=\"Int32\" Name=\"offsets\" "
             "format=\"ascii\">\n";
      for (unsigned int i = 0; i < n; ++i)
        vtu << i + 1 << " ";
      vtu << "\n</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" "
             "format=\"ascii\">\n";
      for (unsigned int i = 0; i < n; ++i)
        vtu << "1 ";
      vtu << "\n</DataArray>\n</Cells>\n<PointData>\n";
      auto scalar = [&](const std::string &name, auto value) {
        vtu << "<DataArray type=\"Float64\" Name=\"" << name
            << "\" format=\"ascii\">\n";
        for (unsigned int i = 0; i < n; ++i)
          vtu << value(i) << " ";
        vtu << "\n</DataArray>\n";
      };
      scalar("pressure", [&](unsigned int i) {
        return p(m * i) / pair_list[i].area;
      });
      scalar("gap", [&](unsigned int i) {
        return u_rel(m * i);
      });
      scalar("status", [&](unsigned int i) {
        return static_cast<double>(static_cast<int>(status[i]));
      });
      vtu << "<DataArray type=\"Float64\" Name=\"contact_force\" "
             "NumberOfComponents=\"3\" format=\"ascii\">\n";
      for (unsigned int i = 0; i < n; ++i)
        {
          const Tensor<1, dim> f = global_force(i, p);
          for (unsigned int d = 0; d < 3; ++d)
            vtu << (d < dim ? f[d] : 0.) << " ";
        }
      vtu << "\n</DataArray>\n";
      if (m > 1)
        {
          vtu << "<DataArray type=\"Float64\" Name=\"slip\" "
                 "NumberOfComponents=\"3\" format=\"ascii\">\n";
          for (unsigned int i = 0; i < n; ++i)
            {
              Tensor<1, dim> s;
              for (unsigned int k = 1; k < m; ++k)
                s += u_rel(m * i + k) * pair_list[i].frame[k];
              for (unsigned int d = 0; d < 3; ++d)
                vtu << (d < dim ? s[d] : 0.) << " ";
            }
          vtu << "\n</DataArray>\n";
        }
      vtu << "</PointData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
    }



    template <int dim>
    void
    ContactStage<dim>::add_summary(base::Json &summary) const
    {
      bool any_gap = false;
      for (const auto &pair : pair_list)
        any_gap = any_gap || pair.gap > 0.;
      bool body_force = false;
      for (const auto &body : bodies)
        body_force = body_force || body->description().body_force.norm() > 0.;

      base::Json effects;
      effects["contact"]                  = true;
      effects["friction"]                 = (n_components > 1);
      effects["tangential_unknowns"]      = (n_components > 1);
      effects["rigid_obstacle"]           = settings.rigid_plane;
      effects["initial_gaps"]             = any_gap;
      effects["body_force"]               = body_force;
      effects["floating_rigid_modes"]     = alpha_modes.size();
      effects["pairs_left_out_supported"] = n_dropped;
      summary["effects"]                  = effects;
      summary["n_contact_pairs"]          = pair_list.size();
      summary["n_contact_unknowns"] = problem.n_rows() + problem.n_alpha();
    }



    template <int dim>
    void
    ContactStage<dim>::add_checks(base::Json &checks) const
    {
      const unsigned int m = n_components;
      if (settings.uniform_pressure > 0.)
        {
          double worst = 0.;
          for (unsigned int i = 0; i < pair_list.size(); ++i)
            worst = std::max(worst,
                             std::abs(p(m * i) / pair_list[i].area /
                                        settings.uniform_pressure -
                                      1.));
          checks["pressure_uniformity"] = worst;
          log << "  pressure uniformity max |p_i/p - 1| = "
              << std::setprecision(3) << std::scientific << worst
              << std::defaultfloat << std::setprecision(6) << std::endl;
        }

      if (settings.hertz_line_load > 0.)
        {
          // Johnson: a = sqrt(4 P R / (pi E*)), p0 = 2 P / (pi a), rigid
          // flat, E* = E / (1 - nu^2).
          const auto  &material = bodies[0]->description().material;
          const double E_star =
            material.youngs_modulus /
            (1. - material.poisson_ratio * material.poisson_ratio);
          const double P = settings.hertz_line_load, R = settings.hertz_radius;
          const double a  = std::sqrt(4. * P * R / (M_PI * E_star));
          const double p0 = 2. * P / (M_PI * a);

          // Pair pressures by distance from the symmetry axis.
          std::vector<std::pair<double, double>> profile;
          for (unsigned int i = 0; i < pair_list.size(); ++i)
            profile.emplace_back(std::abs(pair_list[i].x1[0]),
                                 p(m * i) / pair_list[i].area);
          std::sort(profile.begin(), profile.end());
          double peak = 0.;
          for (const auto &[x, pr] : profile)
            peak = std::max(peak, pr);

          // Half-width: the last loaded pair, refined by the ellipse
          // p^2 = c (a^2 - x^2) through the last two loaded pairs, kept
          // between the last loaded and the first open pair.
          int last = -1;
          for (unsigned int k = 0; k < profile.size(); ++k)
            if (profile[k].second > 1e-6 * peak)
              last = k;
          double a_h = (last >= 0 ? profile[last].first : 0.);
          if (last >= 1)
            {
              const double x1 = profile[last - 1].first,
                           p1 = profile[last - 1].second;
              const double x2 = profile[last].first, p2 = profile[last].second;
              if (p1 > p2)
                {
                  const double a2 = (p1 * p1 * x2 * x2 - p2 * p2 * x1 * x1) /
                                    (p1 * p1 - p2 * p2);
                  double       estimate = std::sqrt(std::max(a2, 0.));
                  const double upper =
                    (last + 1 < int(profile.size()) ? profile[last + 1].first :
                                                      estimate);
                  a_h = std::min(std::max(estimate, x2), upper);
                }
            }

          // L2 distance of the piecewise linear pair profile to Johnson's
          // over |x| <= 1.2 a.
          auto p_h = [&](const double x) {
            if (x <= profile.front().first)
              return profile.front().second;
            for (unsigned int k = 1; k < profile.size(); ++k)
              if (x <= profile[k].first)
                {
                  const double t = (x - profile[k - 1].first) /
                                   (profile[k].first - profile[k - 1].first);
                  return (1 - t) * profile[k - 1].second +
                         t * profile[k].second;
                }
            return profile.back().second;
          };
          double             e2 = 0., n2 = 0.;
          const unsigned int n_samples = 4000;
          for (unsigned int k = 0; k < n_samples; ++k)
            {
              const double x = 1.2 * a * (k + 0.5) / n_samples;
              const double pe =
                (x < a ? p0 * std::sqrt(1. - x * x / (a * a)) : 0.);
              e2 += std::pow(p_h(x) - pe, 2);
              n2 += pe * pe;
            }
          checks["hertz_half_width"]          = a_h;
          checks["hertz_half_width_exact"]    = a;
          checks["hertz_half_width_error"]    = std::abs(a_h / a - 1.);
          checks["hertz_peak_pressure"]       = peak;
          checks["hertz_peak_pressure_exact"] = p0;
          checks["pressure_l2_rel_error"]     = std::sqrt(e2 / n2);
          log << "  Hertz: half-width " << std::setprecision(5) << a_h
              << " (Johnson " << a << "), peak pressure " << peak
              << " (Johnson " << p0 << "), profile L2 error "
              << std::setprecision(3) << std::sqrt(e2 / n2)
              << std::setprecision(6) << std::endl;
        }
    }



    template class ContactStage<2>;
    template class ContactStage<3>;
  } // namespace contact
} // namespace igabde
