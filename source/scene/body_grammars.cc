#include <igabde/base/utilities.h>

#include <igabde/scene/body_grammars.h>
#include <igabde/scene/parameters.h>

#include <deal.II/base/function_parser.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <regex>
#include <sstream>

namespace igabde
{
  namespace scene
  {
    namespace
    {
      /// Face ids and what they are, for messages: "0 (x = lower), ...".
      std::string
      face_list(const std::vector<std::string> &faces)
      {
        std::string list;
        for (unsigned int f = 0; f < faces.size(); ++f)
          list +=
            (f > 0 ? ", " : "") + std::to_string(f) + " (" + faces[f] + ")";
        return list;
      }



      std::string
      component_names(const unsigned int dimension)
      {
        return dimension == 2 ? "x, y" : "x, y, z";
      }



      /// The component 'x', 'y' or 'z' names (0, 1, 2), refused unless it
      /// is one of the scene's; @p where and @p item say where it was read.
      unsigned int
      read_component(const std::string &name,
                     const unsigned int dimension,
                     const std::string &where,
                     const std::string &item)
      {
        const int c = (name == "x" ? 0 :
                       name == "y" ? 1 :
                       name == "z" ? 2 :
                                     -1);
        AssertThrow(c >= 0 && c < static_cast<int>(dimension),
                    base::ExcInput(where + ": '" + name + "' in '" + item +
                                   "' is not a component; use " +
                                   component_names(dimension) +
                                   ", optionally with =value."));
        return c;
      }



      /**
       * Reads the held components of @p names ("x y=0.01") into @p components
       * and @p values; refuses an entry @p item that names none.
       */
      void
      read_held_components(const std::string     &names,
                           const unsigned int     dimension,
                           const std::string     &where,
                           const std::string     &item,
                           std::array<bool, 3>   &components,
                           std::array<double, 3> &values)
      {
        std::istringstream in(names);
        std::string        token;
        bool               any = false;
        while (in >> token)
          {
            const auto         eq = token.find('=');
            const unsigned int c =
              read_component(token.substr(0, eq), dimension, where, item);
            components[c] = true;
            if (eq != std::string::npos)
              {
                const auto v = base::parse_doubles(token.substr(eq + 1), where);
                AssertThrow(v.size() == 1,
                            base::ExcInput(where + ": '" + token +
                                           "' needs one value."));
                values[c] = v[0];
              }
            any = true;
          }
        AssertThrow(any,
                    base::ExcInput(where + ": '" + item +
                                   "' names no component."));
      }



      /// read_faces() of exactly one face.
      unsigned int
      read_face(const std::string &key,
                const PatchFaces  &faces,
                const std::string &where,
                const std::string &item)
      {
        return read_faces(key, faces, where, item, false).front();
      }
    } // namespace



    template <int dim>
    std::shared_ptr<FunctionParser<dim>>
    make_function_parser(const std::vector<std::string> &expressions,
                         const double                    t)
    {
      auto f = std::make_shared<FunctionParser<dim>>(dim);
      f->initialize(dim == 2 ? "x,y,t" : "x,y,z,t",
                    expressions,
                    {{"pi", numbers::PI}},
                    true);
      f->set_time(t);
      return f;
    }



    bool
    check_expressions(const std::vector<std::string> &expressions,
                      const unsigned int              dimension,
                      const std::string              &where)
    {
      std::string all;
      for (const auto &e : expressions)
        all += (all.empty() ? "" : "; ") + e;
      AssertThrow(expressions.size() == dimension,
                  base::ExcInput(where + ": 'function " + all + "' has " +
                                 std::to_string(expressions.size()) +
                                 " expressions; give " +
                                 std::to_string(dimension) +
                                 ", one per component, separated by ';'."));
      // deal.II's FunctionParser prints muparser's report on std::cerr
      // before it throws; the one-line error below says it instead.
      std::ostringstream silenced;
      std::streambuf    *cerr_buffer = std::cerr.rdbuf(silenced.rdbuf());
      try
        {
          // Parse errors show at the first evaluation.
          if (dimension == 2)
            {
              const auto f = make_function_parser<2>(expressions, 0.);
              for (unsigned int c = 0; c < 2; ++c)
                f->value(Point<2>(), c);
            }
          else
            {
              const auto f = make_function_parser<3>(expressions, 0.);
              for (unsigned int c = 0; c < 3; ++c)
                f->value(Point<3>(), c);
            }
        }
      catch (const ExceptionBase &e)
        {
          std::cerr.rdbuf(cerr_buffer);
          AssertThrow(false,
                      base::ExcInput(where + ": cannot evaluate 'function " +
                                     all + "' (" + base::exception_message(e) +
                                     "); write expressions of " +
                                     (dimension == 2 ? "x, y" : "x, y, z") +
                                     " and t in deal.II's FunctionParser "
                                     "syntax, e.g. '-100*(1-x^2)'."));
        }
      std::cerr.rdbuf(cerr_buffer);
      static const std::regex t_variable(
        "(^|[^A-Za-z0-9_])t([^A-Za-z0-9_(]|$)");
      return std::any_of(expressions.begin(),
                         expressions.end(),
                         [](const std::string &e) {
                           return std::regex_search(e, t_variable);
                         });
    }



    std::pair<std::string, std::string>
    split_history(const std::string &entry)
    {
      const auto at = entry.find('@');
      if (at == std::string::npos)
        return {entry, ""};
      return {base::trim(entry.substr(0, at)),
              base::trim(entry.substr(at + 1))};
    }



    std::vector<double>
    read_vector(const std::string &text,
                const unsigned int dimension,
                const std::string &where)
    {
      std::vector<double> v  = base::parse_doubles(text, where);
      bool                ok = (v.size() >= dimension);
      for (unsigned int i = dimension; ok && i < v.size(); ++i)
        ok = (v[i] == 0.);
      AssertThrow(ok,
                  base::ExcInput(where + ": '" + text + "' must have " +
                                 std::to_string(dimension) +
                                 " comma-separated components in this " +
                                 std::to_string(dimension) + "D scene."));
      v.resize(dimension);
      return v;
    }



    std::vector<unsigned int>
    read_faces(const std::string &key,
               const PatchFaces  &faces,
               const std::string &where,
               const std::string &item,
               const bool         several)
    {
      static const std::regex face_pattern(
        "^\\s*(?:([0-9]+)\\.)?([0-9]+)\\s*$");
      const std::size_t n_faces = faces.names.size();
      const std::string form =
        "must be a patch face 0.." + std::to_string(n_faces - 1) +
        (faces.from_file ?
           " (or p.f: face f of patch p of a multi-patch file" +
             std::string(several ? "; several joined by '+'" : "") + ")" :
           std::string(several ? " (several joined by '+')" : "")) +
        " of the " + faces.geometry + ": " + face_list(faces.names) + ".";
      std::vector<unsigned int>      result;
      const std::vector<std::string> terms = base::split(key, '+');
      AssertThrow(several || terms.size() == 1,
                  base::ExcInput(where + ": '" + base::trim(item) +
                                 "' names several faces; give one face "
                                 "here."));
      for (const std::string &term : terms)
        {
          std::smatch match;
          AssertThrow(
            std::regex_match(term, match, face_pattern) &&
              match[2].length() < 3 && std::stoul(match[2].str()) < n_faces &&
              (!match[1].matched || (faces.from_file && match[1].length() < 6)),
            base::ExcInput(where + ": face '" + base::trim(term) + "' " +
                           (base::trim(item) == base::trim(term) ?
                              std::string() :
                              "in '" + base::trim(item) + "' ") +
                           form));
          const unsigned int patch =
            match[1].matched ? std::stoul(match[1].str()) : 0;
          result.push_back(patch * n_faces + std::stoul(match[2].str()));
        }
      return result;
    }



    std::vector<unsigned int>
    read_subdivisions(const std::string &text,
                      const unsigned int dimension,
                      const std::string &where)
    {
      const std::vector<double> n = base::parse_doubles(text, where);
      AssertThrow(n.size() == 1 || n.size() == dimension,
                  base::ExcInput(where + " = '" + text +
                                 "': give one count or one per direction."));
      std::vector<unsigned int> subdivisions(dimension);
      for (unsigned int d = 0; d < dimension; ++d)
        {
          const double count = (n.size() == 1 ? n[0] : n[d]);
          AssertThrow(count >= 1 && count == std::floor(count) && count < 1e4,
                      base::ExcInput(where + " = '" + text +
                                     "': counts must be integers from 1 to "
                                     "9999 (then Discretization/Refinements "
                                     "for finer meshes)."));
          subdivisions[d] = static_cast<unsigned int>(count);
        }
      return subdivisions;
    }



    GradingParameters
    read_grading(const std::string &text,
                 const unsigned int dimension,
                 const std::string &where)
    {
      GradingParameters grading;
      grading.ratio.assign(dimension, 1.);
      grading.toward_high.assign(dimension, false);
      grading.band.assign(dimension, {{0., 0.}});
      for (const std::string &item : base::split(text, ';'))
        {
          if (item.rfind("band", 0) == 0)
            {
              // 'band d: from, to, ratio'.
              const auto [key, value] =
                base::split_entry(item, where, "'band d: from, to, ratio'");
              const std::vector<double> d =
                base::parse_doubles(key.substr(4), where);
              const std::vector<double> v = base::parse_doubles(value, where);
              AssertThrow(d.size() == 1 && d[0] >= 0 && d[0] < dimension &&
                            d[0] == std::floor(d[0]) && v.size() == 3 &&
                            0. <= v[0] && v[0] < v[1] && v[1] <= 1. &&
                            v[2] >= 1. && v[2] <= 1e6,
                          base::ExcInput(
                            where + ": '" + item +
                            "': a band is 'band d: from, to, ratio' with a "
                            "parametric direction d from 0 to " +
                            std::to_string(dimension - 1) +
                            ", 0 <= from < to <= 1 (fractions of the "
                            "direction) and a ratio of the largest span to "
                            "the smallest in [1, 1e6]."));
              const unsigned int dir = static_cast<unsigned int>(d[0]);
              AssertThrow(grading.ratio[dir] == 1.,
                          base::ExcInput(where + ": '" + item +
                                         "': direction " + std::to_string(dir) +
                                         " is graded twice; give one grading "
                                         "per direction."));
              grading.ratio[dir] = v[2];
              grading.band[dir]  = {{v[0], v[1]}};
              continue;
            }
          const auto [face_text, ratio_text] =
            base::split_entry(item, where, "'face: ratio'");
          const std::vector<double> f = base::parse_doubles(face_text, where);
          AssertThrow(f.size() == 1 && f[0] >= 0 && f[0] < 2 * dimension &&
                        f[0] == std::floor(f[0]),
                      base::ExcInput(where + ": face in '" + item +
                                     "' must be a patch face 0.." +
                                     std::to_string(2 * dimension - 1) + "."));
          const unsigned int        face = static_cast<unsigned int>(f[0]);
          const std::vector<double> ratio =
            base::parse_doubles(ratio_text, where);
          AssertThrow(ratio.size() == 1 && ratio[0] >= 1. && ratio[0] <= 1e6,
                      base::ExcInput(where + ": '" + item +
                                     "': the ratio of the largest span to the "
                                     "smallest must lie in [1, 1e6]."));
          AssertThrow(grading.ratio[face / 2] == 1.,
                      base::ExcInput(where + ": '" + item + "': direction " +
                                     std::to_string(face / 2) +
                                     " is graded twice; grade toward one of "
                                     "its faces."));
          grading.ratio[face / 2]       = ratio[0];
          grading.toward_high[face / 2] = (face % 2 == 1);
        }
      return grading;
    }



    std::vector<SupportParameters>
    read_supports(const std::string &text,
                  const PatchFaces  &faces,
                  const std::string &where)
    {
      const unsigned int             dimension = faces.names.size() / 2;
      std::vector<SupportParameters> supports;
      for (const std::string &entry : base::split(text, ';'))
        {
          const auto [item, history] = split_history(entry);
          const auto [key, value] =
            base::split_entry(item, where, "'face: components', e.g. '0: x y'");
          SupportParameters support;
          support.history = history;
          // Faces joined by '+': one support per face, alike.
          const std::vector<unsigned int> support_faces =
            read_faces(key, faces, where, item);
          // 'c = function expression': one component given by an
          // expression of the point, scaled like a value.
          static const std::regex function_entry(
            "^\\s*([xyz])\\s*=\\s*function\\s+(.+)$");
          std::smatch function_match;
          if (std::regex_match(value, function_match, function_entry))
            {
              const int c = function_match[1].str()[0] - 'x';
              AssertThrow(c < static_cast<int>(dimension),
                          base::ExcInput(
                            where + ": '" + item + "': component " +
                            function_match[1].str() + " does not exist in " +
                            std::to_string(dimension) + "D."));
              std::vector<std::string> all(dimension, "0");
              all[c] = base::trim(function_match[2].str());
              AssertThrow(!check_expressions(all, dimension, where),
                          base::ExcInput(
                            where + ": '" + item +
                            "' uses t; a prescribed displacement is scaled "
                            "by its history's factor (write the expression "
                            "of x, y[, z] and choose the history with "
                            "'@ name')."));
              support.components[c]  = true;
              support.expressions[c] = all[c];
            }
          else
            {
              // Components between spaces or commas.
              std::string names = value;
              std::replace(names.begin(), names.end(), ',', ' ');
              read_held_components(names,
                                   dimension,
                                   where,
                                   item,
                                   support.components,
                                   support.values);
            }
          for (const unsigned int face : support_faces)
            {
              support.face = face;
              supports.push_back(support);
            }
        }
      return supports;
    }



    std::vector<TractionParameters>
    read_tractions(const std::string &text,
                   const PatchFaces  &faces,
                   const std::string &where)
    {
      const unsigned int              dimension = faces.names.size() / 2;
      std::vector<TractionParameters> tractions;
      // The components of a function are the next pieces between ';'.
      const std::vector<std::string> pieces = base::split(text, ';');
      for (unsigned int i = 0; i < pieces.size(); ++i)
        {
          auto [item, history]   = split_history(pieces[i]);
          const auto [key, rest] = base::split_entry(
            item,
            where,
            "'face: pressure p', 'face: vector tx, ty', 'face: exact' or "
            "'face: function fx; fy'");
          TractionParameters              traction;
          const std::vector<unsigned int> traction_faces =
            read_faces(key, faces, where, item);
          if (rest.rfind("pressure", 0) == 0)
            {
              traction.kind   = TractionParameters::Kind::pressure;
              traction.values = base::parse_doubles(rest.substr(8), where);
              AssertThrow(traction.values.size() == 1,
                          base::ExcInput(where + ": '" + item +
                                         "' needs one pressure value."));
            }
          else if (rest.rfind("vector", 0) == 0)
            {
              traction.kind   = TractionParameters::Kind::vector;
              traction.values = read_vector(rest.substr(6), dimension, where);
            }
          else if (rest == "exact")
            traction.kind = TractionParameters::Kind::exact;
          else if (rest.rfind("function", 0) == 0)
            {
              traction.kind = TractionParameters::Kind::function;
              traction.expressions.push_back(base::trim(rest.substr(8)));
              while (traction.expressions.size() < dimension &&
                     i + 1 < pieces.size())
                {
                  std::tie(item, history) = split_history(pieces[++i]);
                  traction.expressions.push_back(item);
                }
              traction.uses_t =
                check_expressions(traction.expressions, dimension, where);
            }
          else
            AssertThrow(false,
                        base::ExcInput(where + ": '" + rest +
                                       "' is not 'pressure p', 'vector tx, "
                                       "ty[, tz]', 'exact' or 'function fx; "
                                       "fy[; fz]'."));
          traction.history = history;
          for (const unsigned int face : traction_faces)
            {
              traction.face = face;
              tractions.push_back(traction);
            }
        }
      return tractions;
    }



    int
    read_hold_rotation(const std::string &text,
                       const PatchFaces  &faces,
                       const std::string &where)
    {
      if (base::trim(text).empty())
        return -1;
      return read_face(base::trim(text), faces, where, text);
    }



    std::vector<PointLoadParameters>
    read_point_loads(const std::string &text,
                     const unsigned int dimension,
                     const std::string &where)
    {
      std::vector<PointLoadParameters> point_loads;
      for (const std::string &entry : base::split(text, ';'))
        {
          const auto [item, history] = split_history(entry);
          const auto [location, force] =
            base::split_entry(item, where, "'x, y[, z] : fx, fy[, fz]'");
          point_loads.push_back({read_vector(location, dimension, where),
                                 read_vector(force, dimension, where),
                                 history});
        }
      return point_loads;
    }



    std::vector<PointSupportParameters>
    read_point_supports(const std::string &text,
                        const unsigned int dimension,
                        const std::string &where)
    {
      std::vector<PointSupportParameters> point_supports;
      for (const std::string &full_entry : base::split(text, ';'))
        {
          const auto [entry, history] = split_history(full_entry);
          const auto [location, names] =
            base::split_entry(entry,
                              where,
                              "'x, y[, z] : components', e.g. '0, 0 : x y'");
          PointSupportParameters support;
          support.location = read_vector(location, dimension, where);
          read_held_components(names,
                               dimension,
                               where,
                               base::trim(entry),
                               support.components,
                               support.values);
          support.history = history;
          point_supports.push_back(support);
        }
      return point_supports;
    }



    std::vector<MomentParameters>
    read_moments(const std::string &text,
                 const PatchFaces  &faces,
                 const std::string &where)
    {
      const unsigned int            dimension = faces.names.size() / 2;
      std::vector<MomentParameters> moments;
      for (const std::string &entry : base::split(text, ';'))
        {
          const auto [item, history] = split_history(entry);
          const auto [key, rest] =
            base::split_entry(item,
                              where,
                              dimension == 2 ? "'face: M'" :
                                               "'face: Mx, My, Mz'");
          MomentParameters moment;
          moment.face               = read_face(key, faces, where, item);
          moment.moment             = base::parse_doubles(rest, where);
          const unsigned int n_axes = (dimension == 2 ? 1 : 3);
          AssertThrow(moment.moment.size() == n_axes,
                      base::ExcInput(
                        where + ": '" + item + "' must give " +
                        (dimension == 2 ? std::string("one value (the "
                                                      "moment about z)") :
                                          std::string("three values (Mx, "
                                                      "My, Mz)")) +
                        " in this " + std::to_string(dimension) + "D scene."));
          moment.history = history;
          moments.push_back(moment);
        }
      return moments;
    }



    std::vector<FaceMotionParameters>
    read_face_motions(const std::string &text,
                      const PatchFaces  &faces,
                      const std::string &where)
    {
      const unsigned int                dimension = faces.names.size() / 2;
      std::vector<FaceMotionParameters> face_motions;
      for (const std::string &entry : base::split(text, ';'))
        {
          const auto [item, history] = split_history(entry);
          const std::string form     = dimension == 2 ?
                                         "'face: ux, uy, rz'" :
                                         "'face: ux, uy, uz, rx, ry, rz'";
          const auto [key, rest]     = base::split_entry(item, where, form);
          FaceMotionParameters motion;
          motion.face = read_face(key, faces, where, item);
          // 'face: ... about cx, cy[, cz]': the motion's reference point.
          std::string values = rest;
          if (const auto at = rest.find("about"); at != std::string::npos)
            {
              values        = rest.substr(0, at);
              motion.centre = base::parse_doubles(rest.substr(at + 5), where);
              AssertThrow(motion.centre.size() == dimension,
                          base::ExcInput(where + ": '" + base::trim(item) +
                                         "' must give " +
                                         std::to_string(dimension) +
                                         " coordinates after 'about' (the "
                                         "point the face turns about)."));
            }
          motion.motion = base::parse_doubles(values, where);
          AssertThrow(motion.motion.size() == (dimension == 2 ? 3u : 6u),
                      base::ExcInput(
                        where + ": '" + base::trim(item) + "' must give " +
                        (dimension == 2 ? "three" : "six") + " values, " +
                        form + ", in this " + std::to_string(dimension) +
                        "D scene (every component of the "
                        "face's rigid motion)."));
          for (const auto &other : face_motions)
            AssertThrow(other.face != motion.face,
                        base::ExcInput(where + ": face " +
                                       std::to_string(motion.face) +
                                       " is moved twice; give it one "
                                       "entry."));
          motion.history = history;
          face_motions.push_back(motion);
        }
      return face_motions;
    }



    std::vector<ObstacleMotionParameters>
    read_obstacle_motion(const std::string &text,
                         const unsigned int dimension,
                         const std::string &where)
    {
      const unsigned int n_rotations = (dimension == 2 ? 1u : 3u);
      const std::string  form        = dimension == 2 ?
                                         "'ux, uy' or 'ux, uy, rz'" :
                                         "'ux, uy, uz' or 'ux, uy, uz, rx, ry, rz'";
      std::vector<ObstacleMotionParameters> motion;
      for (const std::string &entry : base::split(text, ';'))
        {
          const auto [item, history]       = split_history(entry);
          const std::vector<double> values = base::parse_doubles(item, where);
          AssertThrow(values.size() == dimension ||
                        values.size() == dimension + n_rotations,
                      base::ExcInput(
                        where + ": '" + base::trim(item) + "' gives " +
                        std::to_string(values.size()) +
                        " values; a term of the obstacle's rigid motion is " +
                        form +
                        " (translation in m, rotation in rad about "
                        "the obstacle's Centre or Plane point), optionally "
                        "followed by '@ history'."));
          ObstacleMotionParameters term;
          term.translation.assign(values.begin(), values.begin() + dimension);
          term.rotation.assign(n_rotations, 0.);
          if (values.size() > dimension)
            term.rotation.assign(values.begin() + dimension, values.end());
          term.history = history;
          motion.push_back(term);
        }
      return motion;
    }



    BodyForceParameters
    read_body_force(const std::string &text,
                    const unsigned int dimension,
                    const std::string &where)
    {
      BodyForceParameters body_force;
      if (base::trim(text).rfind("function", 0) == 0)
        {
          body_force.vector.assign(dimension, 0.);
          body_force.expressions = base::split(base::trim(text).substr(8), ';');
          AssertThrow(!check_expressions(body_force.expressions,
                                         dimension,
                                         where),
                      base::ExcInput(where + " uses t; the body "
                                             "force is scaled by the load "
                                             "factor (write an expression "
                                             "of x, y[, z])."));
        }
      else
        body_force.vector = read_vector(text, dimension, where);
      return body_force;
    }



    std::vector<ProbePoint>
    read_probe_points(const std::string &text,
                      const unsigned int dimension,
                      const std::string &where)
    {
      std::vector<ProbePoint> probes;
      for (const std::string &item : base::split(text, ';'))
        {
          const auto [name, location] =
            base::split_entry(item, where, "'name: x, y[, z]'");
          const std::vector<double> x = base::parse_doubles(location, where);
          AssertThrow(x.size() == dimension,
                      base::ExcInput(where + ": '" + item + "' needs " +
                                     std::to_string(dimension) +
                                     " coordinates ('name: x, y[, z]')."));
          probes.push_back({name, x});
        }
      return probes;
    }



    std::vector<double>
    read_numbers(const std::string &text, const std::string &where)
    {
      return base::parse_doubles(text, where);
    }



    std::vector<double>
    read_point(const std::string &text,
               const unsigned int dimension,
               const std::string &where)
    {
      const auto x = base::parse_doubles(text, where);
      AssertThrow(x.size() == dimension,
                  base::ExcInput(where + " = '" + text + "' must be a " +
                                 std::to_string(dimension) + "D point."));
      return x;
    }



    std::vector<double>
    read_direction(const std::string &text,
                   const unsigned int dimension,
                   const std::string &where)
    {
      const auto e    = base::parse_doubles(text, where);
      double     norm = 0.;
      for (const double v : e)
        norm += v * v;
      AssertThrow(e.size() == dimension && norm > 0.,
                  base::ExcInput(
                    where + " = '" + text + "' must be a non-zero " +
                    std::to_string(dimension) + "D vector, " +
                    (dimension == 2 ? "e.g. '0, 1'" : "e.g. '0, 0, 1'") + "."));
      return e;
    }



    std::vector<std::pair<std::string, std::vector<double>>>
    read_histories(const std::string &text, const std::string &where)
    {
      std::vector<std::pair<std::string, std::vector<double>>> histories;
      for (const std::string &item : base::split(text, ';'))
        {
          const auto [name, values] =
            base::split_entry(item, where, "'name: f1, f2, ...'");
          AssertThrow(!name.empty(),
                      base::ExcInput(where + ": '" + item +
                                     "' has no name; write 'name: f1, f2, "
                                     "...'."));
          AssertThrow(name.find_first_of(" \t,;:@") == std::string::npos &&
                        name != "load" && name != "displacement",
                      base::ExcInput(where + ": '" + name +
                                     "' is not a usable name (one word, "
                                     "not 'load' or 'displacement')."));
          for (const auto &h : histories)
            AssertThrow(h.first != name,
                        base::ExcInput(where + ": '" + name +
                                       "' is declared twice."));
          histories.emplace_back(name,
                                 read_history_factors(values,
                                                      where + "/" + name));
        }
      return histories;
    }



    std::vector<double>
    read_history_factors(const std::string &text, const std::string &where)
    {
      std::vector<double> factors;
      for (const std::string &raw : base::split(text, ','))
        {
          const std::string        item = base::trim(raw);
          std::istringstream       in(item);
          std::string              word;
          std::vector<std::string> words;
          while (in >> word)
            words.push_back(word);
          if (words.empty() || (words[0] != "ramp" && words[0] != "hold"))
            {
              const auto v = base::parse_doubles(item, where);
              factors.insert(factors.end(), v.begin(), v.end());
              continue;
            }
          const bool        ramp  = words[0] == "ramp";
          const std::string usage = ramp ? "'ramp a b n' (n factors from a "
                                           "to b, b the last)" :
                                           "'hold f n' (n factors f)";
          AssertThrow(words.size() == (ramp ? 4u : 3u),
                      base::ExcInput(where + ": '" + item + "' must read " +
                                     usage + "."));
          std::vector<double> v;
          for (unsigned int k = 1; k + 1 < words.size(); ++k)
            {
              char        *stop  = nullptr;
              const double value = std::strtod(words[k].c_str(), &stop);
              AssertThrow(*stop == '\0' && std::isfinite(value),
                          base::ExcInput(where + ": '" + item + "' must read " +
                                         usage + ", but '" + words[k] +
                                         "' is not a number."));
              v.push_back(value);
            }
          char               *end = nullptr;
          const unsigned long n = std::strtoul(words.back().c_str(), &end, 10);
          AssertThrow(*end == '\0' && n >= 1 && n <= 100000 &&
                        words.back().find('-') == std::string::npos,
                      base::ExcInput(where + ": '" + item + "' must read " +
                                     usage +
                                     " with n a whole number from 1 "
                                     "to 100000."));
          for (unsigned long k = 1; k <= n; ++k)
            factors.push_back(
              ramp ?
                k == n ? v[1] : v[0] + (v[1] - v[0]) * double(k) / double(n) :
                v[0]);
        }
      return factors;
    }



    template std::shared_ptr<FunctionParser<2>>
    make_function_parser<2>(const std::vector<std::string> &, double);
    template std::shared_ptr<FunctionParser<3>>
    make_function_parser<3>(const std::vector<std::string> &, double);
  } // namespace scene
} // namespace igabde
