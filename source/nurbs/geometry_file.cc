#include <igabde/base/files.h>
#include <igabde/base/utilities.h>

#include <igabde/nurbs/geometry_file.h>

#include <deal.II/base/data_out_base.h>
#include <deal.II/base/quadrature_lib.h>

#include <algorithm>
#include <boost/property_tree/ptree.hpp>
#include <boost/property_tree/xml_parser.hpp>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>

namespace igabde
{
  namespace nurbs
  {
    namespace
    {
      namespace pt = boost::property_tree;

      /// The attribute @p name of @p node, or @p fallback.
      std::string
      attribute(const pt::ptree   &node,
                const std::string &name,
                const std::string &fallback = "")
      {
        return node.get<std::string>("<xmlattr>." + name, fallback);
      }

      /// The text of @p node.
      std::string
      text(const pt::ptree &node)
      {
        return node.get_value<std::string>();
      }

      /// Every number of @p text (base::parse_doubles), a rational literal
      /// "p/q" as G+Smo writes exact coordinates (filedata/planar's
      /// "1/9") included; @p where ends in ": " as the other messages of
      /// this file.
      std::vector<double>
      numbers(const std::string &text, const std::string &where)
      {
        std::string context = where;
        while (!context.empty() &&
               (context.back() == ' ' || context.back() == ':'))
          context.pop_back();
        if (text.find('/') == std::string::npos)
          return base::parse_doubles(text, context);
        std::string cleaned = text;
        std::replace(cleaned.begin(), cleaned.end(), ',', ' ');
        std::istringstream  in(cleaned);
        std::vector<double> values;
        std::string         token;
        while (in >> token)
          {
            const auto slash = token.find('/');
            if (slash == std::string::npos)
              {
                values.push_back(base::parse_doubles(token, context).front());
                continue;
              }
            const std::string numerator   = token.substr(0, slash);
            const std::string denominator = token.substr(slash + 1);
            const bool one_slash = denominator.find('/') == std::string::npos;
            const std::vector<double> p =
              one_slash ? base::parse_doubles(numerator, context) :
                          std::vector<double>();
            const std::vector<double> q =
              one_slash ? base::parse_doubles(denominator, context) :
                          std::vector<double>();
            AssertThrow(p.size() == 1 && q.size() == 1 && q[0] != 0.,
                        base::ExcInput(context + ": '" + token +
                                       "' is not a number; a fraction reads "
                                       "p/q with q not zero, as 5/18."));
            values.push_back(p[0] / q[0]);
          }
        return values;
      }



      /// A count read from the file: a whole number >= 0.
      unsigned int
      whole(const double x, const std::string &where)
      {
        AssertThrow(x >= 0. && x == std::floor(x) && x < 1e9,
                    base::ExcInput(where + std::to_string(x) +
                                   " is not a patch or side number."));
        return static_cast<unsigned int>(x);
      }

      /// The child element @p tag of @p node, or an input error.
      const pt::ptree &
      child(const pt::ptree   &node,
            const std::string &tag,
            const std::string &where)
      {
        const auto c = node.get_child_optional(tag);
        AssertThrow(c,
                    base::ExcInput(where + "no <" + tag +
                                   "> element; see doc/geometry-files.md "
                                   "for the layout igabde reads."));
        return *c;
      }

      template <int dim>
      NurbsPatch<dim>
      read_patch(const pt::ptree   &node,
                 const std::string &where,
                 bool              &planar_in_3d)
      {
        const std::string type = attribute(node, "type");
        const bool rational    = (type == "TensorNurbs" + std::to_string(dim));
        const pt::ptree &basis = child(node, "Basis", where);
        const pt::ptree &tensor =
          rational ? child(basis, "Basis", where) : basis;
        const std::string expected = "TensorBSplineBasis" + std::to_string(dim);
        AssertThrow(attribute(tensor, "type") == expected,
                    base::ExcInput(where + "the basis is of type '" +
                                   attribute(tensor, "type") + "', expected " +
                                   expected + "."));

        // One BSplineBasis per direction, in the order of their index
        // attribute (or of the file when there is none).
        std::array<KnotVector, dim> knots;
        unsigned int                n_read = 0;
        for (const auto &[tag, b] : tensor)
          {
            if (tag != "Basis")
              continue;
            const unsigned int d =
              whole(numbers(attribute(b, "index", std::to_string(n_read)),
                            where)
                      .at(0),
                    where + "Basis index ");
            AssertThrow(d < dim && attribute(b, "type") == "BSplineBasis",
                        base::ExcInput(where + "expected " +
                                       std::to_string(dim) +
                                       " BSplineBasis elements with index 0 "
                                       "to " +
                                       std::to_string(dim - 1) + "."));
            const pt::ptree  &kv = child(b, "KnotVector", where);
            const std::string direction =
              where + "knot vector of direction " + std::to_string(d) + ": ";
            const std::vector<double> degree =
              numbers(attribute(kv, "degree"), direction);
            AssertThrow(degree.size() == 1 && degree[0] >= 1. &&
                          degree[0] == std::floor(degree[0]),
                        base::ExcInput(direction +
                                       "the degree attribute must be a whole "
                                       "number >= 1."));
            AssertThrow(degree[0] <= KnotVector::max_fast_degree,
                        base::ExcInput(
                          direction + "degree " +
                          std::to_string(static_cast<int>(degree[0])) +
                          " is above the largest supported, " +
                          std::to_string(KnotVector::max_fast_degree) +
                          "; lower it (or refine by knots instead)."));
            try
              {
                knots[d] = KnotVector(static_cast<unsigned int>(degree[0]),
                                      numbers(text(kv), direction));
              }
            catch (const ExceptionBase &e)
              {
                AssertThrow(false,
                            base::ExcInput(where + base::exception_message(e)));
              }
            ++n_read;
          }
        AssertThrow(n_read == dim,
                    base::ExcInput(where + "has " + std::to_string(n_read) +
                                   " knot vectors; a " + type + " needs " +
                                   std::to_string(dim) + "."));
        unsigned int n = 1;
        for (unsigned int d = 0; d < dim; ++d)
          n *= knots[d].n_basis_functions();

        const pt::ptree  &coefs = child(node, "coefs", where);
        const std::string geo_dim =
          attribute(coefs, "geoDim", std::to_string(dim));
        // G+Smo stores planar surfaces in 3D space (geoDim = 3): a 2D scene
        // takes them when every z is zero.
        planar_in_3d               = (dim == 2 && geo_dim == "3");
        const unsigned int columns = planar_in_3d ? 3 : dim;
        AssertThrow(geo_dim == std::to_string(dim) || planar_in_3d,
                    base::ExcInput(
                      where + "geoDim = " + geo_dim +
                      ", but the scene has Dimension = " + std::to_string(dim) +
                      "; a body of a " + std::to_string(dim) +
                      "D scene needs a " + std::to_string(dim) + "D patch in " +
                      std::to_string(dim) + "D space."));
        const std::vector<double> c = numbers(text(coefs), where + "coefs: ");
        AssertThrow(c.size() == columns * n,
                    base::ExcInput(
                      where + "the knot vectors give " + std::to_string(n) +
                      " control points (" + std::to_string(columns * n) +
                      " coordinates), but <coefs> holds " +
                      std::to_string(c.size()) + " numbers; give one row of " +
                      std::to_string(columns) +
                      " coordinates per control point, direction 0 "
                      "fastest."));
        std::vector<Point<dim>> points(n);
        for (unsigned int a = 0; a < n; ++a)
          {
            for (unsigned int d = 0; d < dim; ++d)
              points[a][d] = c[columns * a + d];
            AssertThrow(!planar_in_3d || c[columns * a + 2] == 0.,
                        base::ExcInput(
                          where + "geoDim = 3 and control point " +
                          std::to_string(a) +
                          " has z = " + base::number_text(c[columns * a + 2]) +
                          ", but the scene has Dimension = 2; a 2D scene "
                          "reads a patch stored in 3D space only when it "
                          "lies in the plane z = 0 (every z zero)."));
          }

        std::vector<double> weights(n, 1.);
        if (rational)
          {
            weights = numbers(text(child(basis, "weights", where)),
                              where + "weights: ");
            AssertThrow(weights.size() == n,
                        base::ExcInput(where + std::to_string(n) +
                                       " control points but " +
                                       std::to_string(weights.size()) +
                                       " weights; give one weight per "
                                       "control point."));
            for (unsigned int a = 0; a < n; ++a)
              AssertThrow(weights[a] > 0.,
                          base::ExcInput(where +
                                         "the weight of control "
                                         "point " +
                                         std::to_string(a) + " is " +
                                         std::to_string(weights[a]) +
                                         "; NURBS weights must be "
                                         "positive."));
          }
        return NurbsPatch<dim>(knots, points, weights);
      }

      /// @p n in every direction.
      template <int dim>
      std::array<unsigned int, dim>
      same(const unsigned int n)
      {
        std::array<unsigned int, dim> a;
        a.fill(n);
        return a;
      }

      /// The Gauss points of every knot span (tensor products, direction 0
      /// fastest) and, if @p weights is not null, their weights.
      template <int dim>
      std::vector<Point<dim>>
      gauss_points(const std::array<std::vector<double>, dim> &breaks,
                   const std::array<unsigned int, dim>        &n_points,
                   std::vector<double>                        *weights)
      {
        std::array<std::vector<double>, dim> x, w;
        for (unsigned int d = 0; d < dim; ++d)
          {
            const QGauss<1> gauss(n_points[d]);
            for (unsigned int e = 0; e + 1 < breaks[d].size(); ++e)
              {
                const double h = breaks[d][e + 1] - breaks[d][e];
                for (unsigned int q = 0; q < n_points[d]; ++q)
                  {
                    x[d].push_back(breaks[d][e] + h * gauss.point(q)[0]);
                    w[d].push_back(h * gauss.weight(q));
                  }
              }
          }
        if (weights != nullptr)
          {
            const std::vector<Point<dim>> ww = tensor_product_points<dim>(w);
            weights->clear();
            for (const auto &p : ww)
              {
                double product = 1.;
                for (unsigned int d = 0; d < dim; ++d)
                  product *= p[d];
                weights->push_back(product);
              }
          }
        return tensor_product_points<dim>(x);
      }

      template <int dim>
      std::array<std::vector<double>, dim>
      all_breakpoints(const NurbsPatch<dim> &patch)
      {
        std::array<std::vector<double>, dim> breaks;
        for (unsigned int d = 0; d < dim; ++d)
          breaks[d] = patch.breakpoints(d);
        return breaks;
      }

      std::string
      join(const std::vector<double> &values, const unsigned int per_line)
      {
        std::ostringstream out;
        out << std::setprecision(17);
        for (unsigned int i = 0; i < values.size(); ++i)
          out << (i % per_line == 0 ? "\n" : " ") << values[i];
        out << "\n";
        return out.str();
      }
    } // namespace



    template <int dim>
    MultiPatchGeometry<dim>
    read_geometry_file(const std::string &file_name)
    {
      const std::string where = file_name + ": ";
      AssertThrow(std::filesystem::is_regular_file(file_name),
                  base::ExcInput(where +
                                 "no such file; give the path of a G+Smo "
                                 "XML file, relative to the scene file's "
                                 "folder or absolute."));
      pt::ptree tree;
      try
        {
          pt::read_xml(file_name, tree);
        }
      catch (const pt::xml_parser_error &e)
        {
          AssertThrow(false,
                      base::ExcInput(file_name + ":" +
                                     std::to_string(e.line()) +
                                     ": not well-formed XML (" + e.message() +
                                     "); is the file complete?"));
        }
      const auto root = tree.get_child_optional("xml");
      AssertThrow(root,
                  base::ExcInput(where + "no <xml> root element; a G+Smo "
                                         "file holds <Geometry> elements "
                                         "inside <xml> ... </xml>."));

      // Geometry elements by id (their order in the file when they have
      // none), and the first MultiPatch.
      std::map<int, const pt::ptree *> geometries;
      std::vector<int>                 file_order;
      const pt::ptree                 *multipatch = nullptr;
      for (const auto &[tag, node] : *root)
        if (tag == "Geometry")
          {
            const std::string id_text =
              attribute(node, "id", std::to_string(file_order.size()));
            const std::vector<double> id =
              numbers(id_text, where + "Geometry id: ");
            AssertThrow(id.size() == 1 && id[0] == std::floor(id[0]),
                        base::ExcInput(where + "Geometry id '" + id_text +
                                       "' is not a whole number."));
            AssertThrow(geometries.count(static_cast<int>(id[0])) == 0,
                        base::ExcInput(where +
                                       "two Geometry elements have "
                                       "id " +
                                       id_text + "; give each its own id."));
            geometries[static_cast<int>(id[0])] = &node;
            file_order.push_back(static_cast<int>(id[0]));
          }
        else if (tag == "MultiPatch" && multipatch == nullptr)
          multipatch = &node;

      std::vector<int> ids = file_order;
      if (multipatch != nullptr)
        {
          const pt::ptree  &patches = child(*multipatch, "patches", where);
          const std::string type    = attribute(patches, "type", "id_range");
          const std::vector<double> list =
            numbers(text(patches), where + "patches: ");
          ids.clear();
          if (type == "id_range")
            {
              AssertThrow(list.size() == 2 && list[0] <= list[1],
                          base::ExcInput(where + "<patches type=\"id_range\">"
                                                 " needs two ids, first <= "
                                                 "last."));
              for (int i = static_cast<int>(list[0]);
                   i <= static_cast<int>(list[1]);
                   ++i)
                ids.push_back(i);
            }
          else if (type == "id_index")
            for (const double x : list)
              ids.push_back(static_cast<int>(x));
          else
            AssertThrow(false,
                        base::ExcInput(where + "<patches type=\"" + type +
                                       "\"> is not read; use id_range or "
                                       "id_index."));
        }
      AssertThrow(!ids.empty(),
                  base::ExcInput(where + "no <Geometry> element; the file "
                                         "must hold at least one patch."));

      MultiPatchGeometry<dim>     geometry;
      std::map<int, unsigned int> index_of_id;
      for (const int id : ids)
        {
          const std::string patch_where =
            where + "patch id " + std::to_string(id) + ": ";
          AssertThrow(geometries.count(id) == 1,
                      base::ExcInput(patch_where +
                                     "the MultiPatch lists it, but no "
                                     "<Geometry> has this id."));
          const pt::ptree  &node = *geometries[id];
          const std::string type = attribute(node, "type");
          const std::string d    = std::to_string(dim);
          if (type != "TensorBSpline" + d && type != "TensorNurbs" + d)
            {
              const bool other_dim =
                (type == "TensorBSpline2" || type == "TensorBSpline3" ||
                 type == "TensorNurbs2" || type == "TensorNurbs3");
              AssertThrow(false,
                          base::ExcInput(patch_where + "type '" + type + "' " +
                                         (other_dim ?
                                            "is a patch of another dimension; "
                                            "the scene has Dimension = " +
                                              d + "." :
                                            "is not read; igabde reads "
                                            "TensorBSpline" +
                                              d + " and TensorNurbs" + d +
                                              " patches.")));
            }
          bool planar_in_3d = false;
          geometry.patches.push_back(
            read_patch<dim>(node, patch_where, planar_in_3d));
          if (planar_in_3d)
            geometry.notes.push_back(
              patch_where +
              "stored in 3D space (geoDim = 3) with every z zero: read as a "
              "2D patch.");
          index_of_id[id] = geometry.patches.size() - 1;
          check_jacobian(geometry.patches.back(), patch_where);
          check_patch_closure(geometry.patches.back(), patch_where);
        }

      if (multipatch != nullptr)
        {
          const auto side = [&](const double       patch_id,
                                const double       g_side,
                                const std::string &context) {
            const std::string at = where + context + "patch " +
                                   std::to_string(int(patch_id)) + " side " +
                                   std::to_string(int(g_side)) + ": ";
            AssertThrow(index_of_id.count(static_cast<int>(patch_id)) == 1,
                        base::ExcInput(at + "no such patch in the "
                                            "MultiPatch."));
            AssertThrow(g_side >= 1. && g_side <= 2. * dim &&
                          g_side == std::floor(g_side),
                        base::ExcInput(at + "G+Smo sides are 1 to " +
                                       std::to_string(2 * dim) +
                                       " (west, east, south, north" +
                                       (dim == 3 ? ", front, back" : "") +
                                       ")."));
            return std::make_pair(index_of_id[static_cast<int>(patch_id)],
                                  whole(g_side - 1., at));
          };
          for (const auto &[tag, node] : *multipatch)
            if (tag == "interfaces")
              {
                std::istringstream lines(text(node));
                std::string        line;
                while (std::getline(lines, line))
                  {
                    const std::vector<double> v =
                      numbers(line, where + "interfaces: ");
                    if (v.empty())
                      continue;
                    AssertThrow(v.size() >= 4,
                                base::ExcInput(where +
                                               "interfaces: the line '" +
                                               base::trim(line) +
                                               "' needs at least patch, "
                                               "side, patch, side."));
                    PatchInterface i;
                    const auto     a = side(v[0], v[1], "interface ");
                    const auto     b = side(v[2], v[3], "interface ");
                    i.patch          = {{a.first, b.first}};
                    i.face           = {{a.second, b.second}};
                    for (unsigned int k = 4; k < v.size(); ++k)
                      i.flags.push_back(static_cast<int>(v[k]));
                    geometry.interfaces.push_back(i);
                  }
              }
            else if (tag == "boundary")
              {
                const std::vector<double> v =
                  numbers(text(node), where + "boundary: ");
                AssertThrow(v.size() % 2 == 0,
                            base::ExcInput(where + "boundary: give pairs of "
                                                   "patch and side."));
                for (unsigned int k = 0; k < v.size(); k += 2)
                  geometry.boundary.push_back(
                    side(v[k], v[k + 1], "boundary "));
              }
          check_interfaces(geometry, where);
        }
      return geometry;
    }



    template <int dim>
    void
    write_geometry_file(const MultiPatchGeometry<dim> &geometry,
                        std::ostream                  &out)
    {
      pt::ptree         xml;
      const std::string d = std::to_string(dim);
      for (unsigned int p = 0; p < geometry.patches.size(); ++p)
        {
          const NurbsPatch<dim> &patch = geometry.patches[p];
          pt::ptree              tensor;
          tensor.put("<xmlattr>.type", "TensorBSplineBasis" + d);
          for (unsigned int k = 0; k < dim; ++k)
            {
              pt::ptree b;
              b.put("<xmlattr>.type", "BSplineBasis");
              b.put("<xmlattr>.index", k);
              pt::ptree kv;
              kv.put("<xmlattr>.degree", patch.degree(k));
              kv.put_value(join(patch.knot_vector(k).knots(),
                                patch.knot_vector(k).knots().size()));
              b.add_child("KnotVector", kv);
              tensor.add_child("Basis", b);
            }
          std::vector<double> weights, coefs;
          for (unsigned int a = 0; a < patch.n_control_points(); ++a)
            {
              weights.push_back(patch.weight(a));
              for (unsigned int k = 0; k < dim; ++k)
                coefs.push_back(patch.control_point(a)[k]);
            }
          pt::ptree basis;
          basis.put("<xmlattr>.type", "TensorNurbsBasis" + d);
          basis.add_child("Basis", tensor);
          basis.put("weights", join(weights, 1));
          pt::ptree node;
          node.put("<xmlattr>.type", "TensorNurbs" + d);
          node.put("<xmlattr>.id", p);
          node.add_child("Basis", basis);
          pt::ptree c;
          c.put("<xmlattr>.geoDim", dim);
          c.put_value(join(coefs, dim));
          node.add_child("coefs", c);
          xml.add_child("Geometry", node);
        }
      if (geometry.patches.size() > 1 || !geometry.interfaces.empty())
        {
          pt::ptree mp;
          mp.put("<xmlattr>.parDim", dim);
          mp.put("<xmlattr>.id", geometry.patches.size());
          pt::ptree patches;
          patches.put("<xmlattr>.type", "id_range");
          patches.put_value("0 " + std::to_string(geometry.patches.size() - 1));
          mp.add_child("patches", patches);
          std::ostringstream interfaces, boundary;
          interfaces << "\n";
          for (const auto &i : geometry.interfaces)
            {
              interfaces << i.patch[0] << ' ' << i.face[0] + 1 << ' '
                         << i.patch[1] << ' ' << i.face[1] + 1;
              for (const int f : i.flags)
                interfaces << ' ' << f;
              interfaces << "\n";
            }
          boundary << "\n";
          for (const auto &[p, f] : geometry.boundary)
            boundary << p << ' ' << f + 1 << "\n";
          mp.put("interfaces", interfaces.str());
          mp.put("boundary", boundary.str());
          xml.add_child("MultiPatch", mp);
        }
      pt::ptree tree;
      tree.add_child("xml", xml);
      pt::write_xml(out,
                    tree,
                    pt::xml_writer_make_settings<std::string>(' ', 1));
    }



    template <int dim>
    void
    write_control_net_vtu(const MultiPatchGeometry<dim> &geometry,
                          std::ostream                  &out)
    {
      std::vector<DataOutBase::Patch<dim, dim>> cells;
      for (unsigned int p = 0; p < geometry.patches.size(); ++p)
        {
          const NurbsPatch<dim>        &patch = geometry.patches[p];
          std::array<unsigned int, dim> n;
          for (unsigned int d = 0; d < dim; ++d)
            n[d] = patch.n_control_points(d);
          // Every cell of the net: its lower tensor index runs over
          // n[d] - 1 in each direction.
          std::array<std::vector<double>, dim> lower;
          for (unsigned int d = 0; d < dim; ++d)
            for (unsigned int i = 0; i + 1 < n[d]; ++i)
              lower[d].push_back(i);
          for (const Point<dim> &corner : tensor_product_points<dim>(lower))
            {
              DataOutBase::Patch<dim, dim> cell;
              cell.n_subdivisions = 1;
              cell.data.reinit(2, GeometryInfo<dim>::vertices_per_cell);
              for (unsigned int v = 0; v < GeometryInfo<dim>::vertices_per_cell;
                   ++v)
                {
                  std::array<unsigned int, dim> ijk;
                  for (unsigned int d = 0; d < dim; ++d)
                    ijk[d] =
                      static_cast<unsigned int>(corner[d]) + ((v >> d) & 1u);
                  const unsigned int a = patch.control_point_index(ijk);
                  cell.vertices[v]     = patch.control_point(a);
                  cell.data(0, v)      = patch.weight(a);
                  cell.data(1, v)      = p;
                }
              cell.patch_index = cells.size();
              cells.push_back(cell);
            }
        }
      DataOutBase::write_vtu(cells,
                             {"weight", "patch"},
                             {},
                             base::vtu_flags(cells),
                             out);
    }



    template <int dim>
    void
    check_jacobian(const NurbsPatch<dim> &patch, const std::string &where)
    {
      double     smallest = std::numeric_limits<double>::max();
      double     largest  = 0.;
      double     lowest = 0., highest = 0.;
      Point<dim> at_smallest;
      for (const Point<dim> &xi :
           gauss_points<dim>(all_breakpoints(patch), same<dim>(4), nullptr))
        {
          const double det = determinant(patch.jacobian(xi));
          lowest           = std::min(lowest, det);
          highest          = std::max(highest, det);
          largest          = std::max(largest, std::abs(det));
          if (std::abs(det) < smallest)
            {
              smallest    = std::abs(det);
              at_smallest = xi;
            }
        }
      std::ostringstream at;
      at << " at x = (" << patch.value(at_smallest) << ")";
      AssertThrow(!(lowest < 0. && highest > 0.),
                  base::ExcInput(
                    where + "det(dx/dxi) changes sign (from " +
                    std::to_string(lowest) + " to " + std::to_string(highest) +
                    "): the map folds over itself; check the control net "
                    "(e.g. two rows of control points crossing)."));
      AssertThrow(largest > 0. && smallest > 1e-10 * largest,
                  base::ExcInput(
                    where + "det(dx/dxi) vanishes inside the patch" + at.str() +
                    ": the map collapses there; check the "
                    "control net for coincident rows."));
    }



    template <int dim>
    void
    check_patch_closure(const NurbsPatch<dim> &patch, const std::string &where)
    {
      const double diameter   = control_net_diameter(patch);
      const auto   breaks     = all_breakpoints(patch);
      const auto   face_value = [&](const unsigned int face) {
        return face % 2 == 0 ? breaks[face / 2].front() :
                                 breaks[face / 2].back();
      };
      // The face's measure: 4 Gauss points per span and face direction,
      // |cof(J) e_d| the face's area (length) element.
      for (unsigned int face = 0; face < 2 * dim; ++face)
        {
          const unsigned int                   d = face / 2;
          std::array<std::vector<double>, dim> b = breaks;
          std::array<unsigned int, dim>        n;
          n.fill(4);
          std::vector<double> weights;
          b[d]                                  = {0., 1.};
          n[d]                                  = 1;
          double                        measure = 0.;
          const std::vector<Point<dim>> points =
            gauss_points<dim>(b, n, &weights);
          for (unsigned int q = 0; q < points.size(); ++q)
            {
              Point<dim> xi = points[q];
              xi[d]         = face_value(face);
              measure +=
                weights[q] * cofactor_column(patch.jacobian(xi), d).norm();
            }
          std::ostringstream m;
          m << where << "face " << face << " (G+Smo side " << face + 1
            << ") collapses: its " << (dim == 2 ? "length" : "area") << " is "
            << measure
            << ", a pole where its control points are one point but "
               "separate unknowns, so the body would be punctured there "
               "(gluing a patch to itself is not built); model the part "
               "away from the pole, e.g. a sector of a sphere as "
               "contrib/geometry/sphere-sector writes it.";
          AssertThrow(measure > 1e-8 * std::pow(diameter, dim - 1),
                      base::ExcInput(m.str()));
        }
      // Two faces that coincide.
      for (unsigned int f = 0; f < 2 * dim; ++f)
        for (unsigned int g = f + 1; g < 2 * dim; ++g)
          {
            std::array<std::vector<double>, dim> samples;
            for (unsigned int d = 0; d < dim; ++d)
              if (d == f / 2)
                samples[d] = {face_value(f)};
              else
                for (unsigned int e = 0; e + 1 < breaks[d].size(); ++e)
                  for (unsigned int k = 0; k < 5; ++k)
                    samples[d].push_back(breaks[d][e] +
                                         (breaks[d][e + 1] - breaks[d][e]) * k /
                                           4.);
            const auto on_g = [&](const Point<dim> &xi) {
              const Point<dim> x = patch.value(xi);
              return x.distance(patch.value(
                       patch.closest_point_on_face(g, x))) <= 1e-8 * diameter;
            };
            // The face's middle first: off g for every pair of faces that
            // merely share an edge, so the samples are tried only where
            // the faces may coincide.
            Point<dim> middle;
            for (unsigned int d = 0; d < dim; ++d)
              middle[d] =
                (d == f / 2 ? face_value(f) :
                              0.5 * (breaks[d].front() + breaks[d].back()));
            bool all_on = on_g(middle);
            if (all_on)
              for (const Point<dim> &xi : tensor_product_points<dim>(samples))
                if (!on_g(xi))
                  {
                    all_on = false;
                    break;
                  }
            AssertThrow(
              !all_on,
              base::ExcInput(
                where + "faces " + std::to_string(f) + " and " +
                std::to_string(g) + " (G+Smo sides " + std::to_string(f + 1) +
                " and " + std::to_string(g + 1) +
                ") coincide: the patch closes on itself (a full ring or "
                "tube), and a body of one patch would have a slit there "
                "(gluing a patch to itself is not built); model a "
                "symmetric part of it instead, e.g. a half or a quarter "
                "with symmetry supports on the cuts."));
          }
    }



    template <int dim>
    void
    check_interfaces(const MultiPatchGeometry<dim> &geometry,
                     const std::string             &where)
    {
      for (const PatchInterface &i : geometry.interfaces)
        {
          const std::string at =
            where + "interface (patch " + std::to_string(i.patch[0]) +
            " face " + std::to_string(i.face[0]) + ", patch " +
            std::to_string(i.patch[1]) + " face " + std::to_string(i.face[1]) +
            ", in file order and face = side - 1): ";
          AssertThrow(i.patch[0] != i.patch[1] || i.face[0] != i.face[1],
                      base::ExcInput(at + "a face cannot meet itself."));
          const double diameter =
            std::max(control_net_diameter(geometry.patches[i.patch[0]]),
                     control_net_diameter(geometry.patches[i.patch[1]]));
          for (unsigned int s = 0; s < 2; ++s)
            {
              const NurbsPatch<dim> &from  = geometry.patches[i.patch[s]];
              const NurbsPatch<dim> &to    = geometry.patches[i.patch[1 - s]];
              const unsigned int     fixed = i.face[s] / 2;
              std::array<std::vector<double>, dim> samples;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  const std::vector<double> b = from.breakpoints(d);
                  if (d == fixed)
                    samples[d] = {i.face[s] % 2 == 0 ? b.front() : b.back()};
                  else
                    for (unsigned int e = 0; e + 1 < b.size(); ++e)
                      for (unsigned int k = 0; k < 5; ++k)
                        samples[d].push_back(b[e] + (b[e + 1] - b[e]) * k / 4.);
                }
              for (const Point<dim> &xi : tensor_product_points<dim>(samples))
                {
                  const Point<dim> x = from.value(xi);
                  const Point<dim> on_face =
                    to.value(to.closest_point_on_face(i.face[1 - s], x));
                  const double       distance = x.distance(on_face);
                  std::ostringstream m;
                  m << at << "the point (" << x << ") of patch " << i.patch[s]
                    << " lies " << distance
                    << " from the other face; the two faces of an interface "
                       "must coincide (check the patch and side numbers).";
                  AssertThrow(distance <= 1e-8 * diameter,
                              base::ExcInput(m.str()));
                }
            }
        }
    }



    template <int dim>
    double
    control_net_diameter(const NurbsPatch<dim> &patch)
    {
      Point<dim> lo = patch.control_point(0), hi = lo;
      for (unsigned int a = 0; a < patch.n_control_points(); ++a)
        for (unsigned int d = 0; d < dim; ++d)
          {
            lo[d] = std::min(lo[d], patch.control_point(a)[d]);
            hi[d] = std::max(hi[d], patch.control_point(a)[d]);
          }
      return (hi - lo).norm();
    }



    template <int dim>
    double
    patch_measure(const NurbsPatch<dim> &patch, const unsigned int n_points)
    {
      // Gauss error per span ~ (h / 2 rho)^(2n) for an analytic integrand
      // whose nearest complex singularity lies rho parametric units away:
      // 13 points on a single 90-degree arc span reach round-off, so
      // n = 17 / ln(4 k) with k spans in the direction keeps that
      // accuracy with fewer points on finer spans.
      std::array<unsigned int, dim> n;
      for (unsigned int d = 0; d < dim; ++d)
        n[d] =
          n_points > 0 ?
            n_points :
            std::max<unsigned int>(
              patch.degree(d) + 1,
              std::ceil(17. / std::log(4. * patch.knot_vector(d).n_spans())));
      std::vector<double>           weights;
      const std::vector<Point<dim>> points =
        gauss_points<dim>(all_breakpoints(patch), n, &weights);
      double sum = 0.;
      for (unsigned int q = 0; q < points.size(); ++q)
        sum += std::abs(determinant(patch.jacobian(points[q]))) * weights[q];
      return sum;
    }



    template MultiPatchGeometry<2>
    read_geometry_file<2>(const std::string &);
    template MultiPatchGeometry<3>
    read_geometry_file<3>(const std::string &);
    template void
    write_geometry_file<2>(const MultiPatchGeometry<2> &, std::ostream &);
    template void
    write_geometry_file<3>(const MultiPatchGeometry<3> &, std::ostream &);
    template void
    write_control_net_vtu<2>(const MultiPatchGeometry<2> &, std::ostream &);
    template void
    write_control_net_vtu<3>(const MultiPatchGeometry<3> &, std::ostream &);
    template void
    check_jacobian<2>(const NurbsPatch<2> &, const std::string &);
    template void
    check_jacobian<3>(const NurbsPatch<3> &, const std::string &);
    template void
    check_patch_closure<2>(const NurbsPatch<2> &, const std::string &);
    template void
    check_patch_closure<3>(const NurbsPatch<3> &, const std::string &);
    template void
    check_interfaces<2>(const MultiPatchGeometry<2> &, const std::string &);
    template void
    check_interfaces<3>(const MultiPatchGeometry<3> &, const std::string &);
    template double
    patch_measure<2>(const NurbsPatch<2> &, unsigned int);
    template double
    patch_measure<3>(const NurbsPatch<3> &, unsigned int);
    template double
    control_net_diameter<2>(const NurbsPatch<2> &);
    template double
    control_net_diameter<3>(const NurbsPatch<3> &);
  } // namespace nurbs
} // namespace igabde
