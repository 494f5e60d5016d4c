#ifndef igabde_nurbs_geometry_builders_h
#define igabde_nurbs_geometry_builders_h

#include <igabde/nurbs/nurbs_patch.h>

#include <deal.II/base/point.h>

#include <array>

namespace igabde
{
  namespace nurbs
  {
    using namespace dealii;

    /**
     * @brief Exact NURBS patches of the project's test and scene geometries.
     *
     * All parametric boxes are [0, 1]^dim and the knot vectors open. Faces
     * follow NurbsPatch: face f lies at the low (f even) or high (f odd) end
     * of parametric direction f/2, which is also the boundary id of the
     * colorized parametric Triangulation. Circular arcs are degree-2 rational
     * segments with middle weight cos(half the arc angle) (P&T A7.1), so
     * circles are exact to round-off. Note that the parametrization is not
     * by arc length.
     */

    /**
     * @brief Axis-parallel rectangle (2D) or box (3D) [lo, hi], degree 1 in
     * every direction, one span.
     *
     * Direction d runs along x_d. Faces: 0: x = lo_x, 1: x = hi_x,
     * 2: y = lo_y, 3: y = hi_y, 4: z = lo_z, 5: z = hi_z.
     */
    template <int dim>
    NurbsPatch<dim>
    make_box(const Point<dim> &lo, const Point<dim> &hi);

    /**
     * @brief Quarter annulus r0 <= r <= r1, 0 <= theta <= 90 deg in the x-y
     * plane, centred at the origin.
     *
     * Direction 0 is radial (degree 1, knots [0 0 1 1]), direction 1 angular
     * from theta = 0 (the +x axis) to theta = 90 deg (+y), degree 2, knots
     * [0 0 0 1 1 1]. Right-handed. Faces: 0: inner arc r = r0, 1: outer arc
     * r = r1, 2: theta = 0 (segment on the x axis, y = 0), 3: theta = 90 deg
     * (segment on the y axis, x = 0).
     */
    NurbsPatch<2>
    make_quarter_annulus(const double r0, const double r1);

    /**
     * @brief Quarter of a thick cylinder: the quarter annulus of
     * make_quarter_annulus() (2D), or in 3D the same annulus in the x-y
     * plane extruded along z in [0, height] (direction 2, degree 1).
     *
     * Faces: 0: r = r0, 1: r = r1, 2: theta = 0 (y = 0), 3: theta = 90 deg
     * (x = 0), and in 3D 4: z = 0, 5: z = height. Right-handed.
     */
    template <int dim>
    NurbsPatch<dim>
    make_thick_cylinder_quarter(const double r0,
                                const double r1,
                                const double height = 1.);

    /**
     * @brief The curved beam of scene B2: the quarter annulus r0 <= r <= r1
     * in the x-z plane, angle theta from +x towards +z (x = r cos theta,
     * z = r sin theta), extruded along y in [0, width].
     *
     * Directions: 0 radial (degree 1), 1 circumferential (degree 2, theta
     * from 0 to 90 deg), 2 width along y (degree 1). Faces: 0: r = r0
     * (inner curved face), 1: r = r1 (outer curved face), 2: theta = 0 (the
     * end in the plane z = 0), 3: theta = 90 deg (the end in the plane
     * x = 0), 4: y = 0, 5: y = width. This parametrization is left-handed
     * (det dx/dxi < 0); NurbsPatch::orientation() accounts for it.
     */
    NurbsPatch<3>
    make_curved_beam(const double r0, const double r1, const double width);

    /**
     * @brief The quarter plate with a circular hole of Hughes, Cottrell and
     * Bazilevs (CMAME 194 (2005), sec. 6.2), mirrored into the first
     * quadrant: [0, L]^2 minus the disc of radius R at the origin; the
     * classical two-element coarsest mesh, exact.
     *
     * Direction 0 runs from the hole to the outer edges (degree 2, knots
     * [0 0 0 1 1 1]), direction 1 from the x axis (theta = 0) to the y axis
     * (degree 2, knots [0 0 0 1/2 1 1 1], the knot at theta = 45 deg).
     * For R = 1, L = 4 the control net is exactly the published one (its
     * middle row is (R+L)/2 times (1,0), (1,0.3), (0.3,1), (0,1) for other
     * R, L). Faces: 0: the hole r = R, 1: the outer edges x = L
     * (xi_1 < 1/2) and y = L (xi_1 > 1/2), 2: symmetry edge y = 0,
     * 3: symmetry edge x = 0. The map is singular at the outer corner
     * (L, L) (two coincident control points), as in the original.
     */
    NurbsPatch<2>
    make_plate_with_hole(const double R = 1., const double L = 4.);

    /**
     * @brief A quarter of a disc of radius R for the 2D Hertz scene: the
     * disc is centred at (0, R), so its lowest point (0, 0) touches the line
     * y = 0; the patch is its lower-right quarter {x >= 0, y <= R}.
     *
     * Both directions are degree 2 with knots [0 0 0 1 1 1] (one element);
     * corners: xi = (0,0) at the bottom point (0, 0), (1,0) at the 45-degree
     * point (R sin 45, R (1 - cos 45)), (0,1) at the centre (0, R), (1,1) at
     * (R, R). Faces:
     *  - 0: the vertical symmetry segment x = 0, from (0,0) to the centre;
     *  - 1: the upper arc, from the 45-degree point to (R, R);
     *  - 2: the lower arc, from the bottom point (0,0) to the 45-degree
     *    point: the contact face;
     *  - 3: the horizontal cut y = R through the centre, from (0, R) to
     *    (R, R): where the load goes.
     * Right-handed, no collapsed edge: det J > 0 everywhere except at the
     * single corner xi = (1, 0), the 45-degree point, where faces 1 and 2
     * meet at a straight angle (the arc is smooth there), so that J has rank
     * one at that point only; no quadrature point ever sits there. The
     * interior control point is the bilinear Coons blend of the homogeneous
     * boundary net.
     */
    NurbsPatch<2>
    make_hertz_quarter_disc(const double R);

    /**
     * @brief The lower half {y <= c_y} of the disc of radius @p R centred at
     * @p centre = c: its flat face is the diameter y = c_y on top, its
     * lowest point c - (0, R) at the middle of the bottom face.
     *
     * Both directions are degree 2 with knots [0 0 0 1 1 1] (one element);
     * direction 0 runs from left to right, direction 1 from the bottom arc
     * up to the diameter. Polar angles theta are measured from +x at c.
     * Faces:
     *  - 0: the left arc, theta from 225 deg (bottom) to 180 deg (c_x - R,
     *    c_y);
     *  - 1: the right arc, theta from 315 deg to 360 deg (c_x + R, c_y);
     *  - 2: the bottom arc, theta from 225 deg to 315 deg, through the
     *    lowest point at its middle (xi_0 = 1/2): the contact face;
     *  - 3: the diameter y = c_y, from (c_x - R, c_y) to (c_x + R, c_y):
     *    where a load goes.
     * Right-handed. det J > 0 everywhere except at the two corners
     * xi = (0, 0) and (1, 0) (theta = 225 and 315 deg), where the bottom arc
     * meets a side arc at a straight angle and J has rank one; no
     * quadrature point sits there. The interior control point is the
     * bilinear Coons blend of the homogeneous boundary net (as
     * make_hertz_quarter_disc()).
     */
    NurbsPatch<2>
    make_half_disc(const Point<2> &centre, const double R);

    /**
     * @brief The full disc of radius @p R centred at @p centre, one
     * element of degree 2 in both directions (the nine-point disc: corner
     * control points on the circle at 45, 135, 225, 315 deg, the centre
     * control point at c with weight sqrt(2) - 1).
     *
     * Direction 0 runs from left to right, direction 1 from bottom to top.
     * Faces, each a 90-degree arc: 0: left, theta from 225 deg to 135 deg;
     * 1: right, theta from 315 deg to 45 deg; 2: bottom, theta from 225
     * deg to 315 deg (lowest point c - (0, R) at its middle); 3: top, theta
     * from 135 deg to 45 deg (highest point at its middle). Right-handed;
     * J has rank one at the four corners (straight angles on the circle)
     * and is regular elsewhere.
     */
    NurbsPatch<2>
    make_full_disc(const Point<2> &centre, const double R);

    /**
     * @brief make_half_disc() (@p full false) or make_full_disc() (@p full
     * true) in the x-y plane around (c_x, c_y), extruded along z from c_z
     * to c_z + @p height (direction 2, degree 1), c = @p base_centre.
     *
     * Faces 0-3 as the 2D patch (now surfaces along z), 4: z = c_z,
     * 5: z = c_z + height. Right-handed.
     */
    NurbsPatch<3>
    make_cylinder(const Point<3> &base_centre,
                  const double    R,
                  const double    height,
                  const bool      full);

    /**
     * @brief Raises the degree of every direction of @p patch to at least
     * @p degree (k-refinement when followed by knot insertion).
     */
    template <int dim>
    void
    elevate_to_degree(NurbsPatch<dim> &patch, const unsigned int degree);

    /**
     * @brief Splits every span of direction d into @p n_spans[d] equal
     * parametric parts by knot insertion (the geometry is unchanged); e.g.
     * {8, 16, 8} on a one-span beam gives B2's 8 x 16 x 8 mesh. (The
     * array size is written so that it is not deduced: dim comes from
     * @p patch.)
     *
     * With @p grading[d] = r > 1 the parts of direction d grow
     * geometrically instead, the largest r times the smallest, the
     * smallest at the low end of the direction (or at its high end if
     * @p toward_high[d]): the knots of the N = n_spans[d] * (base spans)
     * parts lie at (q^j - 1) / (q^N - 1) of the direction, q = r^(1/(N-1)).
     * The base breakpoints stay; a graded knot that falls on one is not
     * inserted again.
     *
     * With a band, @p bands[d] = {from, to} with 0 <= from < to <= 1, the
     * parts of direction d are smallest, of one size h, over that band
     * (fractions of the direction) and grow by a factor 1.25 per part away
     * from it up to r h (r = @p grading[d] > 1): the part size is
     * h(s) = min(r h, h + (2/9) dist(s, band)) (neighbouring parts then
     * differ by (1 + 1/9)/(1 - 1/9) = 1.25), h chosen so that the N parts
     * fill the direction, the knots where the integral of 1/h(s) from the
     * low end reaches 1, 2, ..., N - 1.
     */
    template <int dim>
    void
    subdivide(
      NurbsPatch<dim>                                               &patch,
      const std::array<unsigned int, static_cast<std::size_t>(dim)> &n_spans,
      const std::array<double, static_cast<std::size_t>(dim)> &grading     = {},
      const std::array<bool, static_cast<std::size_t>(dim)>   &toward_high = {},
      const std::array<std::array<double, 2>, static_cast<std::size_t>(dim)>
        &bands = {});

    /**
     * @brief The interior knots (fractions of a direction, increasing) of
     * @p n parts graded toward the band [@p from, @p to] with size ratio
     * @p ratio, as subdivide() places them.
     */
    std::vector<double>
    band_graded_fractions(const unsigned int n,
                          const double       from,
                          const double       to,
                          const double       ratio);
  } // namespace nurbs
} // namespace igabde

#endif
