#ifndef igabde_scene_contact_setup_h
#define igabde_scene_contact_setup_h

#include <igabde/contact/contact_stage.h>

#include <igabde/scene/parameters.h>

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

namespace igabde
{
  namespace scene
  {
    /**
     * @brief The contact layer's settings from the scene: faces, pairing,
     * algorithm and path, the solvers' tolerances, the bodies' estimated
     * factor entries @p factor_entries (for Contact/Path = auto, from the
     * run's size estimate), @p memory_path_reason (non-empty: auto takes
     * the full path, the condensed one would not fit in memory), with
     * @p log for the solver's lines and
     * @p scene_file for messages.
     */
    contact::ContactSettings
    make_contact_settings(const AllParameters       &parameters,
                          const std::string         &scene_file,
                          const std::vector<double> &factor_entries,
                          const std::string         &memory_path_reason,
                          std::ostream              &log);

    /**
     * @brief What summary.json says of the scene's physics and, with
     * @p contact (the contact stage's summary), of its contact set-up:
     * "effects" (contact, friction, obstacle, gaps, body force, floating
     * modes, load steps) and the pairs, unknowns, algorithm, path and its
     * reason and cost inputs, the full-system solver, the penalty factors.
     */
    void
    record_setup(const AllParameters           &parameters,
                 const contact::ContactSummary *contact,
                 const bool                     body_force,
                 nlohmann::json                &summary);
  } // namespace scene
} // namespace igabde

#endif
