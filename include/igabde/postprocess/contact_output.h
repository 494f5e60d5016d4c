#ifndef igabde_postprocess_contact_output_h
#define igabde_postprocess_contact_output_h

#include <igabde/contact/contact_stage.h>

#include <string>
#include <vector>

namespace igabde
{
  namespace postprocess
  {
    /**
     * @brief Writes the pairs of a load step as a CSV table (full
     * precision): pair, x, y[, z], area, gap, p_n[, p_t1[, p_t2]],
     * pressure[, slip_t1[, slip_t2]], status.
     */
    template <int dim>
    void
    write_pair_csv(const std::vector<contact::PairState<dim>> &pairs,
                   const std::string                          &filename);

    /**
     * @brief Writes the pairs of a load step as a VTU point cloud (deal.II's
     * DataOutBase, binary): pressure, gap, status (0 open, 1 stick, 2 slip),
     * the contact force on Body 1 and, with friction, the slip.
     */
    template <int dim>
    void
    write_pair_vtu(const std::vector<contact::PairState<dim>> &pairs,
                   const std::string                          &filename);
  } // namespace postprocess
} // namespace igabde

#endif
