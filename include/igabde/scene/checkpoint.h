#ifndef igabde_scene_checkpoint_h
#define igabde_scene_checkpoint_h

#include <igabde/contact/contact_stage.h>

#include <igabde/scene/run_record.h>

#include <deal.II/lac/vector.h>

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace igabde
{
  namespace scene
  {
    using namespace dealii;

    /**
     * @brief What a later run needs to continue a load path after a
     * finished step (Output/Checkpoint, `igabde SCENE --restart FOLDER`):
     * the step, its history factors, the displacement of every body at
     * finite strain (a body at small strain is recomputed from its load
     * cases), the contact stage's state (pair forces, rigid-mode
     * amplitudes, the contact part of the displacement, the friction
     * history: ContactStage::State), the records and warnings of the
     * finished steps, and the scene's parameters (without Output), which a
     * restart must match.
     *
     * Written as checkpoint-NNNN.json in the output folder, one file per
     * finished step, each atomically (a file that exists is whole); the
     * numbers with 17 significant digits, so that they read back to the
     * bit (doc/user-guide.md, "Restart").
     */
    struct Checkpoint
    {
      /// The last finished step (1-based).
      unsigned int step = 0;
      /// Its history factors (LoadPathParameters::history_factors()).
      std::vector<double> factors;
      /// Per body: its displacement at finite strain, empty at small.
      std::vector<Vector<double>> finite_state;
      /// The contact stage's state, in a scene with contact.
      std::optional<nlohmann::json> contact;
      /// The finished steps' records and the warnings so far.
      std::vector<StepRecord>  records;
      std::vector<std::string> warnings;
      /// The scene's parameters (parameters.json without Output).
      nlohmann::json parameters;
    };

    /// The file of step @p step's checkpoint in @p directory.
    std::string
    checkpoint_file(const std::string &directory, const unsigned int step);

    /// Writes @p checkpoint to checkpoint_file() (atomically).
    void
    write_checkpoint(const std::string &directory,
                     const Checkpoint  &checkpoint);

    /**
     * @brief The newest checkpoint in @p directory (the highest step);
     * throws an input error naming the folder when it has none.
     */
    Checkpoint
    read_checkpoint(const std::string &directory);

    /**
     * @brief The parameters of a run as a checkpoint keeps them: the
     * folder's parameters.json without the Output subsection (which a
     * restart may change).
     */
    nlohmann::json
    scene_parameters(const std::string &directory);

    /// The same of the JSON text @p text of ParameterHandler::JSON.
    nlohmann::json
    scene_parameters_of(const std::string &text);

    /**
     * @brief Refuses a restart in @p directory, with one input error, when
     * the folder holds no checkpoint or its newest was written by a scene
     * whose parameters (without Output) are not @p scene; names the first
     * parameter that differs.
     */
    void
    check_restart(const std::string &directory, const nlohmann::json &scene);

    /// The state of @p stage as a checkpoint keeps it.
    template <int dim>
    nlohmann::json
    contact_state_to_json(const contact::ContactStage<dim> &stage);

    /// Restores @p stage to the state @p state (contact_state_to_json()).
    template <int dim>
    void
    restore_contact_state(contact::ContactStage<dim> &stage,
                          const nlohmann::json       &state);

    /// A load step's record read back from its to_json().
    StepRecord
    step_record_from_json(const nlohmann::json &j);
  } // namespace scene
} // namespace igabde

#endif
