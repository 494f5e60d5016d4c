#include <igabde/postprocess/exact_solutions.h>

#include <cmath>

namespace igabde
{
  namespace postprocess
  {
    elasticity::ExactSolution<2>
    kirsch_solution(const double                            T,
                    const double                            a,
                    const elasticity::IsotropicMaterial<2> &material)
    {
      const double E  = material.youngs_modulus;
      const double nu = material.poisson_ratio;
      const double mu = E / (2. * (1. + nu));
      const double kappa =
        (material.plane_model == elasticity::PlaneModel::plane_strain ?
           3. - 4. * nu :
           (3. - nu) / (1. + nu));

      elasticity::ExactSolution<2> exact;
      exact.displacement = [=](const Point<2> &x) {
        const double r = x.norm(), theta = std::atan2(x[1], x[0]);
        const double c = T * a / (8. * mu);
        Tensor<1, 2> u;
        u[0] = c * (r / a * (kappa + 1.) * std::cos(theta) +
                    2. * a / r *
                      ((1. + kappa) * std::cos(theta) + std::cos(3. * theta)) -
                    2. * std::pow(a / r, 3) * std::cos(3. * theta));
        u[1] = c * (r / a * (kappa - 3.) * std::sin(theta) +
                    2. * a / r *
                      ((1. - kappa) * std::sin(theta) + std::sin(3. * theta)) -
                    2. * std::pow(a / r, 3) * std::sin(3. * theta));
        return u;
      };
      exact.stress = [=](const Point<2> &x) {
        const double          r = x.norm(), theta = std::atan2(x[1], x[0]);
        const double          a2 = a * a / (r * r), a4 = a2 * a2;
        SymmetricTensor<2, 2> s;
        s[0][0] =
          T * (1. - a2 * (1.5 * std::cos(2. * theta) + std::cos(4. * theta)) +
               1.5 * a4 * std::cos(4. * theta));
        s[1][1] =
          T * (-a2 * (0.5 * std::cos(2. * theta) - std::cos(4. * theta)) -
               1.5 * a4 * std::cos(4. * theta));
        s[0][1] =
          T * (-a2 * (0.5 * std::sin(2. * theta) + std::sin(4. * theta)) +
               1.5 * a4 * std::sin(4. * theta));
        return s;
      };
      return exact;
    }



    template <int dim>
    elasticity::ExactSolution<dim>
    lame_solution(const double                              a,
                  const double                              b,
                  const double                              p,
                  const elasticity::IsotropicMaterial<dim> &material)
    {
      const double E  = material.youngs_modulus;
      const double nu = material.poisson_ratio;
      const double k  = a * a * p / (b * b - a * a);
      // u_r = r eps_tt from the hoop strain of the stresses below: plane
      // strain (and the 3D cylinder with its ends held) eps_tt = ((1 - nu)
      // s_tt - nu s_rr) (1 + nu) / E, plane stress eps_tt = (s_tt - nu
      // s_rr) / E. The stresses do not depend on the model.
      const bool plane_stress =
        dim == 2 &&
        material.plane_model == elasticity::PlaneModel::plane_stress;

      elasticity::ExactSolution<dim> exact;
      exact.displacement = [=](const Point<dim> &x) {
        const double r = std::hypot(x[0], x[1]);
        const double u_r =
          plane_stress ? k / E * ((1. - nu) * r + (1. + nu) * b * b / r) :
                         (1. + nu) * k / E * ((1. - 2. * nu) * r + b * b / r);
        Tensor<1, dim> u;
        u[0] = u_r * x[0] / r;
        u[1] = u_r * x[1] / r;
        return u;
      };
      exact.stress = [=](const Point<dim> &x) {
        const double            r    = std::hypot(x[0], x[1]);
        const double            s_rr = k * (1. - b * b / (r * r));
        const double            s_tt = k * (1. + b * b / (r * r));
        const double            c = x[0] / r, s = x[1] / r;
        SymmetricTensor<2, dim> sigma;
        sigma[0][0] = s_rr * c * c + s_tt * s * s;
        sigma[1][1] = s_rr * s * s + s_tt * c * c;
        sigma[0][1] = (s_rr - s_tt) * c * s;
        if (dim == 3)
          sigma[dim - 1][dim - 1] = nu * (s_rr + s_tt); // plane strain
        return sigma;
      };
      return exact;
    }



    template elasticity::ExactSolution<2>
    lame_solution<2>(const double,
                     const double,
                     const double,
                     const elasticity::IsotropicMaterial<2> &);
    template elasticity::ExactSolution<3>
    lame_solution<3>(const double,
                     const double,
                     const double,
                     const elasticity::IsotropicMaterial<3> &);
  } // namespace postprocess
} // namespace igabde
