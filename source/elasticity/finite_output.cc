#include <igabde/elasticity/finite_output.h>

#include <deal.II/base/symmetric_tensor.h>

#include <algorithm>
#include <cmath>

namespace igabde
{
  namespace elasticity
  {
    template <int dim>
    std::vector<std::string>
    finite_strain_field_names()
    {
      std::vector<std::string> names;
      const char               xyz[] = "xyz";
      for (const std::string prefix : {"strain_", "stress_"})
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = i; j < dim; ++j)
            names.push_back(prefix + xyz[i] + xyz[j]);
      names.emplace_back("von_mises");
      names.emplace_back("det_F");
      names.emplace_back("largest_stretch");
      return names;
    }



    template <int dim>
    double
    largest_stretch(const Tensor<2, dim> &F)
    {
      const auto lambda_squared = eigenvalues(right_cauchy_green(F));
      double     largest =
        *std::max_element(lambda_squared.begin(), lambda_squared.end());
      if (dim == 2)
        largest = std::max(largest, 1.);
      return std::sqrt(std::max(largest, 0.));
    }



    template <int dim>
    void
    finite_strain_fields(const Tensor<2, dim>            &grad_u,
                         const HyperelasticMaterial<dim> &law,
                         double                          *values)
    {
      const Tensor<2, dim>          F = deformation_gradient(grad_u);
      const SymmetricTensor<2, dim> C = right_cauchy_green(F);
      const double                  J = determinant(F);
      SymmetricTensor<2, dim>       E = C;
      for (unsigned int d = 0; d < dim; ++d)
        E[d][d] -= 1.;
      E *= 0.5;
      SymmetricTensor<2, dim> sigma;
      double                  sigma_33 = 0.;
      if (J > 0.)
        {
          sigma = cauchy_stress(F, law.second_piola_kirchhoff(C));
          if (dim == 2)
            sigma_33 = law.out_of_plane_second_piola(C) / J;
        }
      unsigned int k = 0;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = i; j < dim; ++j)
          values[k++] = E[i][j];
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = i; j < dim; ++j)
          values[k++] = sigma[i][j];
      SymmetricTensor<2, 3> s;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = i; j < dim; ++j)
          s[i][j] = sigma[i][j];
      if (dim == 2)
        s[2][2] = sigma_33;
      const SymmetricTensor<2, 3> deviatoric = deviator(s);
      values[k++] = std::sqrt(1.5 * (deviatoric * deviatoric));
      values[k++] = J;
      values[k++] = largest_stretch(F);
    }



    template std::vector<std::string>
    finite_strain_field_names<2>();
    template std::vector<std::string>
    finite_strain_field_names<3>();
    template double
    largest_stretch(const Tensor<2, 2> &);
    template double
    largest_stretch(const Tensor<2, 3> &);
    template void
    finite_strain_fields(const Tensor<2, 2> &,
                         const HyperelasticMaterial<2> &,
                         double *);
    template void
    finite_strain_fields(const Tensor<2, 3> &,
                         const HyperelasticMaterial<3> &,
                         double *);
  } // namespace elasticity
} // namespace igabde
