// The contact state a preloaded complex eigenvalue analysis is linearised
// about (Scene/Analysis = preloaded cea): the static preload's pad nodes in
// contact, or each pad node's fraction of time in contact in a braking
// run's contact history (Preload/Contact state); the interface mask of the
// structural model follows the nearest pad node.

#include <deal.II/base/mpi.h>

#include <squeal/analyses/cea.h>
#include <squeal/analyses/preload.h>
#include <squeal/io/contact_history.h>

#include <memory>
#include <sstream>
#include <stdexcept>

namespace squeal
{
  namespace analyses
  {
    using namespace dealii;

    namespace
    {
      // The value of the node nearest to x, for the interface mask; records
      // the largest distance met in *farthest when it is given.
      std::function<double(const Point<3> &)>
      nearest_node_value(const std::vector<std::pair<Point<3>, double>> &nodes,
                         const std::shared_ptr<double> &farthest)
      {
        return [nodes, farthest](const Point<3> &x) {
          double best = 1e300, value = 0.;
          for (const auto &[p, v] : nodes)
            if (p.distance(x) < best)
              {
                best  = p.distance(x);
                value = v;
              }
          if (farthest)
            *farthest = std::max(*farthest, best);
          return value;
        };
      }

      // Preload/Contact state = braking history: per pad node of the
      // history, the fraction of the window's samples in contact (stick or
      // slip); its mean pressure over the window into `pressure` [Pa]; the
      // largest distance from a node to its nearest other node into
      // `spacing` [m].
      std::vector<std::pair<Point<3>, double>>
      history_contact_fraction(
        const parameters::Preload                &preload,
        std::vector<std::pair<Point<3>, double>> &pressure,
        double                                   &spacing,
        ConditionalOStream                       &pcout)
      {
        const io::ContactHistory h =
          io::read_contact_history(preload.contact_history);
        h.check(preload.contact_history);
        const double t0 =
          preload.contact_window.empty() ? -1e300 : preload.contact_window[0];
        const double t1 =
          preload.contact_window.empty() ? 1e300 : preload.contact_window[1];
        std::vector<std::size_t> samples;
        for (std::size_t k = 0; k < h.n_samples(); ++k)
          if (h.time[k] >= t0 && h.time[k] <= t1)
            samples.push_back(k);
        if (h.n_nodes() < 2)
          throw std::runtime_error(
            "Preload/Contact history " + preload.contact_history + " has " +
            std::to_string(h.n_nodes()) +
            " pad node(s); a contact state needs the nodes of the pad faces");
        if (samples.empty())
          {
            std::ostringstream what;
            what << "Preload/Contact history window: the history "
                 << preload.contact_history << " has no sample in [" << t0
                 << ", " << t1 << "] s (its samples span "
                 << (h.time.empty() ? 0. : h.time.front()) << " to "
                 << (h.time.empty() ? 0. : h.time.back())
                 << " s); give a window inside them, or none";
            throw std::runtime_error(what.str());
          }
        std::vector<std::pair<Point<3>, double>> nodes;
        double                                   mean_fraction = 0;
        pressure.clear();
        for (std::size_t j = 0; j < h.n_nodes(); ++j)
          {
            const auto &c          = h.coordinates[j];
            double      in_contact = 0, p = 0;
            for (const std::size_t k : samples)
              {
                in_contact += h.status[j][k] != 0;
                p += h.p_N[j][k];
              }
            const Point<3> x(c[0], c[1], c[2]);
            nodes.emplace_back(x, in_contact / samples.size());
            pressure.emplace_back(x, p / samples.size());
            mean_fraction += nodes.back().second / h.n_nodes();
          }
        spacing = 0;
        for (const auto &[p, v] : nodes)
          {
            double nearest = 1e300;
            for (const auto &[q, w] : nodes)
              if (&p != &q)
                nearest = std::min(nearest, p.distance(q));
            spacing = std::max(spacing, nearest);
          }
        pcout << "Contact state from the braking history "
              << preload.contact_history << ": " << h.n_nodes()
              << " pad nodes, " << samples.size() << " samples from "
              << h.time[samples.front()] << " to " << h.time[samples.back()]
              << " s, mean fraction of time in contact " << mean_fraction
              << std::endl;
        return nodes;
      }
    } // namespace

    std::function<void()>
    ComplexEigenvalueAnalysis::set_contact_state(
      std::vector<std::pair<dealii::Point<3>, double>> &pressure)
    {
      if (prm.preload.contact_state == "braking history")
        {
          double     spacing = 0; // the history's node spacing [m]
          const auto nodes =
            history_contact_fraction(prm.preload, pressure, spacing, pcout);
          // the largest interface-point-to-node distance [m]
          const auto farthest   = std::make_shared<double>(0.);
          model->interface_mask = nearest_node_value(nodes, farthest);
          return [this, farthest, spacing]() {
            const double d = Utilities::MPI::max(*farthest, comm);
            if (d > 2 * spacing + 1e-12)
              throw std::runtime_error(
                "Preload/Contact history " + prm.preload.contact_history +
                ": its pad nodes do not cover this scene's pad faces (an "
                "interface point lies " +
                std::to_string(d) +
                " m from the nearest history node, more than twice the "
                "history's node spacing " +
                std::to_string(spacing) +
                " m): the history is of another scene or mesh");
          };
        }
      // The preload at the file's nominal parameters, written into
      // preload/; the interface of the CEA then lives where the pad stayed
      // in contact (nearest pad node's status).
      parameters::AllParameters pre = prm;
      pre.output.directory          = work_dir + "/preload";
      pre.output.overwrite          = true;
      analyses::PreloadAnalysis preload(pre, handler, comm);
      preload.run();
      const contact::MortarOperators                  &op = preload.interface();
      std::vector<std::pair<dealii::Point<3>, double>> nodes;
      for (unsigned int j = 0; j < op.n_slave(); ++j)
        {
          nodes.emplace_back(op.slave_points[j],
                             preload.solution().status[j] != 0 ? 1. : 0.);
          pressure.emplace_back(op.slave_points[j],
                                preload.solution().nodal_pressure[j]);
        }
      model->interface_mask = nearest_node_value(nodes, nullptr);
      return {};
    }
  } // namespace analyses
} // namespace squeal
