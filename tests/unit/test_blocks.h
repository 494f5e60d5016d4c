// Elastic NURBS blocks for the contact kernels' unit tests: a box of
// degree 2 cut into given spans and held on one face, in either
// discretisation (E = 1000, nu = 0.3).

#ifndef igabde_tests_test_blocks_h
#define igabde_tests_test_blocks_h

#include <igabde/nurbs/geometry_builders.h>

#include <igabde/discretization/body.h>
#include <igabde/discretization/body_description.h>

#include <array>
#include <memory>

namespace test_blocks
{
  using namespace igabde;
  using namespace dealii;

  /// The block [@p lo, @p hi] of @p spans, degree 2, held in every
  /// component on face @p held_face, set up.
  template <int dim>
  std::unique_ptr<discretization::Body<dim>>
  block(const discretization::Type           type,
        const Point<dim>                    &lo,
        const Point<dim>                    &hi,
        const std::array<unsigned int, dim> &spans,
        const types::boundary_id             held_face)
  {
    discretization::BodyDescription<dim> d;
    d.name                    = "block";
    d.material.youngs_modulus = 1000.;
    d.material.poisson_ratio  = 0.3;
    d.geometry                = nurbs::make_box<dim>(lo, hi);
    nurbs::elevate_to_degree(d.geometry, 2);
    nurbs::subdivide(d.geometry, spans);
    discretization::DirichletCondition<dim> support;
    support.boundary_id = held_face;
    support.components.fill(true);
    d.dirichlet.push_back(support);
    discretization::DiscretizationSettings settings;
    settings.type   = type;
    settings.degree = 2;
    auto body       = discretization::create_body<dim>(d, settings);
    body->setup_system();
    return body;
  }

  /// block() with @p n spans in every direction, held on its first face
  /// across the last direction (the bottom).
  template <int dim>
  std::unique_ptr<discretization::Body<dim>>
  block(const discretization::Type type,
        const Point<dim>          &lo,
        const Point<dim>          &hi,
        const unsigned int         n)
  {
    std::array<unsigned int, dim> spans;
    spans.fill(n);
    return block<dim>(type, lo, hi, spans, 2 * (dim - 1));
  }
} // namespace test_blocks

#endif
