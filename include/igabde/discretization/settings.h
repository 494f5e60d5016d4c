#ifndef igabde_discretization_settings_h
#define igabde_discretization_settings_h

#include <string>

namespace igabde
{
  namespace discretization
  {
    /**
     * @brief How the scene discretises bodies.
     */
    struct DiscretizationSettings
    {
      /// "nurbs" or "lagrange".
      std::string type = "nurbs";
      /// Polynomial degree (NURBS: degree after elevation; Lagrange: FE_Q).
      unsigned int degree = 2;
      /// Extra uniform h-refinements of the scene's base mesh.
      unsigned int refinements = 0;
      /// Linear solver: "direct", "umfpack" or "cg-amg".
      std::string linear_solver = "direct";
      /// Relative tolerance of the iterative solver.
      double linear_tolerance = 1e-12;
      /// Subdivisions per cell and direction in the VTU output.
      unsigned int output_subdivisions = 4;
      /// Where contact pair points sit on a NURBS face: "greville" (images
      /// of the Greville abscissae), "knots" (the knot grid) or "gauss"
      /// (the face's Gauss points). A Lagrange body uses its face nodes
      /// whatever this says.
      std::string pair_placement = "greville";
    };
  } // namespace discretization
} // namespace igabde

#endif
