#ifndef igabde_contact_path_cost_h
#define igabde_contact_path_cost_h

#include <igabde/base/choice_names.h>

#include <string>
#include <vector>

namespace igabde
{
  namespace contact
  {
    /**
     * @brief What the choice between the condensed and the full contact path
     * (Contact/Path = auto) knows before anything is factorised.
     */
    struct PathCostInputs
    {
      /// Contact unknowns m (pairs times components per pair).
      double contact_unknowns = 0.;
      /// Face unknowns n_I of each deformable body: the unknowns the pair
      /// points move (the size of its Schur complement).
      std::vector<double> face_unknowns;
      /// Entries of each deformable body's sparse factor (the estimate of
      /// scene/size_estimate.h, from the mesh alone).
      std::vector<double> factor_entries;
      /// Newton iterations expected over the whole load path.
      double newton_iterations = 0.;
      /// Space dimension of the bodies (2 or 3): a factor entry costs
      /// more in 3D (PathCostConstants::sparse_3d).
      unsigned int dimension = 3;
    };

    /**
     * @brief Seconds per unit of the model's work terms, measured on this
     * project's machine (doc/performance.md, "Choosing the contact path").
     */
    struct PathCostConstants
    {
      /// Dense B-Newton: seconds per m^3/3 (one LAPACK factorisation of the
      /// reduced Newton matrix, all pairs closed).
      double dense = 0.;
      /// Condensation: seconds per (n_I^3/3 + n_I^2 m + n_I m^2) of each
      /// body (the Schur complement, its factorisation and C S^-1 C^T).
      double schur = 0.;
      /// Sparse factorisation of the coupled matrix, 2D bodies: seconds
      /// per factor entry and factorisation (measured: the cost per
      /// iteration grows in proportion to the factor's entries over the
      /// sizes this project runs, not as their 3/2 power).
      double sparse_2d = 0.;
      /// The same for 3D bodies (about three times the 2D figure: more
      /// flops per entry in the larger fronts).
      double sparse_3d = 0.;
      /// Newton iterations assumed per load step.
      double iterations_per_step = 0.;

      /// The constants measured on this machine.
      static PathCostConstants
      measured();
    };

    /**
     * @brief The estimated seconds of both paths and the choice.
     */
    /** @brief Contact/Path. */
    enum class Path
    {
      /// The dense condensed problem from the Schur complements.
      condensed,
      /// The coupled system of displacements, forces and rigid modes.
      full,
      /// The path the cost model (estimate_path_costs()) estimates cheaper.
      automatic
    };

    /** @brief The names of Path as the scene writes them. */
    inline constexpr base::ChoiceNames<Path, 3> path_names = {
      {{Path::condensed, "condensed"},
       {Path::full, "full"},
       {Path::automatic, "auto"}}};

    /** @brief The name of @p path as the scene writes it. */
    inline std::string
    to_string(const Path path)
    {
      return base::name_of(path_names, path);
    }

    struct PathCostEstimate
    {
      /// Estimated seconds of the parts in which the paths differ.
      double condensed_seconds = 0., full_seconds = 0.;
      /// Path::condensed or Path::full.
      Path path = Path::condensed;
      /// One line: both estimates and the terms that decide.
      std::string reason;
    };

    /**
     * @brief The cost model of Contact/Path = auto. With N the expected
     * Newton iterations, L_b the factor entries and n_I,b the face
     * unknowns of body b and m the contact unknowns:
     * @code
     *   condensed = schur sum_b (n_I^3/3 + n_I^2 m + n_I m^2)
     *             + dense N m^3/3
     *   full      = sparse_d N sum_b L_b
     * @endcode
     * with sparse_d the constant of the bodies' dimension.
     * The bodies' own factorisation is left out: both paths do it once (the
     * Schur complement rides on it). The full path is chosen when it is
     * estimated cheaper.
     */
    PathCostEstimate
    estimate_path_costs(const PathCostInputs    &inputs,
                        const PathCostConstants &constants);
  } // namespace contact
} // namespace igabde

#endif
