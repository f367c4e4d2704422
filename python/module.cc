// ramap._core: the compiled half of `import ramap` (python/ramap/__init__.py is the other). It
// binds what is slow or stateful: the mapper, feature extraction and matching, evaluation and the
// models. Every call that works releases the GIL; Ctrl-C stops it cleanly at its next step.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <iostream>

#include "model_bindings.h"
#include "ramap/io/trajectory.h"
#include "ramap/jobs/mapper_job.h"
#include "ramap/jobs/mapper_output.h"
#include "ramap/jobs/model_evaluation.h"
#include "ramap/jobs/reconstruct_job.h"
#include "ramap/mapper/mapper_options.h"
#include "ramap/util/error.h"
#include "ramap/util/run_observer.h"

namespace py = pybind11;

namespace ramap::python {

namespace {

// Turns Python's Ctrl-C (checked in the thread that called, holding the GIL for a moment) into a
// stop of the run, and passes each stage to the progress callback. A Python exception raised in
// either is kept and raised again once the run has unwound.
class PythonRunObserver : public RunObserver {
 public:
  // Made with the GIL held, in the thread that calls ramap. Only Python's main thread receives
  // Ctrl-C, so a call from another thread is never asked to stop by a signal.
  explicit PythonRunObserver(py::object progress)
      : progress_(std::move(progress)),
        on_main_thread_(py::module_::import("threading")
                            .attr("current_thread")()
                            .is(py::module_::import("threading").attr("main_thread")())) {}

  void OnStage(const std::string& stage, double seconds, const std::string& message) override {
    if (progress_.is_none() || error_) return;
    py::gil_scoped_acquire gil;
    try {
      progress_(stage, seconds, message);
    } catch (py::error_already_set& error) {
      error_ = std::make_unique<py::error_already_set>(std::move(error));
    }
  }

  bool StopRequested() override {
    if (error_) return true;
    if (!on_main_thread_) return false;
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) error_ = std::make_unique<py::error_already_set>();
    return error_ != nullptr;
  }

  // Raises the kept Python exception, if any (with the GIL held).
  bool HasKeptError() const { return error_ != nullptr; }

  void RaiseKeptError() {
    if (!error_) return;
    std::unique_ptr<py::error_already_set> error = std::move(error_);
    error->restore();
    throw py::error_already_set();
  }

  ~PythonRunObserver() override {
    if (!error_) return;
    py::gil_scoped_acquire gil;
    error_.reset();
  }

 private:
  py::object progress_;
  bool on_main_thread_;
  std::unique_ptr<py::error_already_set> error_;
};

// Options from Python, already flattened to {"Section.option": "text"} by __init__.py; a wrong
// name or value raises ValueError with the command line's message.
template <typename Settings>
Settings SettingsFromText(const OptionTable<Settings>& table,
                          const std::map<std::string, std::string>& values) {
  Settings settings;
  for (const auto& [name, text] : values) SetOption(table, name, text, &settings);
  return settings;
}

MapperOptions MapperOptionsFromText(const std::map<std::string, std::string>& values) {
  return SettingsFromText(MapperOptionTable(), values);
}

// Runs `work` with the GIL released and `observer` installed; a Python exception the observer
// kept (Ctrl-C, or one raised by the progress callback) is raised once the work has unwound.
template <typename Work>
void RunObserved(PythonRunObserver* observer, Work&& work) {
  std::exception_ptr failure;
  {
    py::gil_scoped_release release;
    const ScopedRunObserver scope(observer);
    try {
      work();
    } catch (const RunStopped&) {
      // Raised below, as the Python exception that asked for the stop.
    } catch (...) {
      failure = std::current_exception();
    }
  }
  // Ctrl-C (or the progress callback's exception) first, even when a worker's exception
  // unwound the run before the stop reached it.
  if (observer->HasKeptError()) observer->RaiseKeptError();
  if (failure) std::rethrow_exception(failure);
}

// Runs `map` (which returns a MapperResult) under a Python observer and gives __init__.py what it
// wants: (models moved into Python, largest first; the summary as JSON text; why nothing was
// reconstructed, empty when something was).
template <typename Map>
py::tuple ObservedMapping(const py::object& progress, Map map) {
  PythonRunObserver observer(progress);
  MapperResult result;
  std::string failure;
  RunObserved(&observer, [&]() {
    try {
      result = map();
    } catch (const NothingReconstructed& nothing) {
      failure = nothing.what();
    }
  });
  py::list models;
  for (Reconstruction& model : result.reconstructions) models.append(py::cast(std::move(model)));
  const std::string summary = failure.empty() ? MapperSummaryToJson(result.summary).dump() : "{}";
  return py::make_tuple(models, summary, failure);
}

// What global_mapping returns to __init__.py: the models (largest first, moved into Python), the
// summary as JSON text, and why nothing was reconstructed (empty when something was).
py::tuple GlobalMapping(const std::string& database_path, const std::string& image_path,
                        const std::string& output_path,
                        const std::map<std::string, std::string>& options,
                        const py::object& progress, bool log) {
  MapperJob job;
  job.database_path = database_path;
  job.image_path = image_path;
  job.output_path = output_path;
  job.options = MapperOptionsFromText(options);
  job.command = "ramap.global_mapping";
  return ObservedMapping(
      progress, [&]() { return RunMapperJob(job, log ? &std::cout : nullptr, &std::cerr); });
}

py::tuple Reconstruct(const std::string& image_path, const std::string& output_path,
                      const std::map<std::string, std::string>& options,
                      const std::string& image_list, const py::object& progress, bool log) {
  ReconstructJob job;
  job.image_path = image_path;
  job.image_list = image_list;
  job.output_path = output_path;
  job.options = SettingsFromText(ReconstructOptionTable(), options);
  job.command = "ramap.reconstruct";
  return ObservedMapping(progress, [&]() {
    return RunReconstructJob(job, log ? &std::cout : nullptr, &std::cerr).mapping;
  });
}

size_t ExtractFeaturesInto(const std::string& image_path, const std::string& database_path,
                           const std::map<std::string, std::string>& options,
                           const std::string& image_list, bool log) {
  const FeatureOptions settings = SettingsFromText(ExtractionOptionTable(), options);
  PythonRunObserver observer{py::none()};
  size_t num_images = 0;
  RunObserved(&observer, [&]() {
    num_images = ExtractFeaturesToDatabase(image_path, image_list, database_path, settings,
                                           log ? &std::cout : nullptr, &std::cerr);
  });
  return num_images;
}

py::object MatchDatabaseFeatures(const std::string& database_path,
                                 const std::map<std::string, std::string>& options, bool log) {
  const FeatureOptions settings = SettingsFromText(MatchingOptionTable(), options);
  PythonRunObserver observer{py::none()};
  std::string summary;
  RunObserved(&observer, [&]() {
    summary = MatchingSummaryToJson(
                  MatchDatabaseFile(database_path, settings, log ? &std::cout : nullptr))
                  .dump();
  });
  return py::module_::import("json").attr("loads")(summary);
}

py::dict EvaluateModelPoses(const std::string& model_path, const std::string& ground_truth,
                            const std::string& format, const std::string& image_list,
                            const std::string& database_path,
                            const std::map<std::string, std::string>& options) {
  ModelEvaluationInput input{model_path, ground_truth, GroundTruthFormatFromName(format),
                             image_list, database_path};
  const PoseEvaluationOptions settings = SettingsFromText(PoseEvaluationOptionTable(), options);
  settings.Check();
  PoseEvaluation evaluation;
  {
    py::gil_scoped_release release;
    evaluation = EvaluateModel(input, settings);
  }
  return py::module_::import("json").attr("loads")(PoseEvaluationToJson(evaluation).dump());
}

void BindOptions(py::module_& m) {
  m.def(
      "mapper_option_names", []() { return OptionNames(MapperOptionTable()); },
      "every mapper option's name, as the command line spells it without the dashes");
  m.def(
      "reconstruct_option_names", []() { return OptionNames(ReconstructOptionTable()); },
      "every option of reconstruct: extraction, matching, the mapper's, loop closure");
  m.def(
      "mapper_option_defaults",
      []() {
        const MapperOptions defaults;
        std::map<std::string, std::string> values;
        for (const auto& d : MapperOptionTable()) {
          if (d.ignored_because.empty()) values[d.name] = d.text(defaults);
        }
        return values;
      },
      "every mapper option's default, as text");
  m.def(
      "check_mapper_options",
      [](const std::map<std::string, std::string>& values) {
        MapperOptions options = MapperOptionsFromText(values);
        options.Check();
      },
      "raises ValueError with the command line's message for a wrong name or value");
}

}  // namespace

}  // namespace ramap::python

PYBIND11_MODULE(_core, m) {
  using namespace ramap::python;
  m.doc() = "ramap's compiled core: motion-averaging structure from motion";
  py::register_exception<ramap::InputError>(m, "InputError", PyExc_ValueError);
  BindModel(m);
  BindOptions(m);
  m.def("global_mapping", &GlobalMapping, py::arg("database_path"), py::arg("image_path"),
        py::arg("output_path"), py::arg("options"), py::arg("progress"), py::arg("log"));
  m.def("reconstruct", &Reconstruct, py::arg("image_path"), py::arg("output_path"),
        py::arg("options"), py::arg("image_list"), py::arg("progress"), py::arg("log"));
  m.def("extract_features", &ExtractFeaturesInto, py::arg("image_path"), py::arg("database_path"),
        py::arg("options"), py::arg("image_list"), py::arg("log"));
  m.def("match", &MatchDatabaseFeatures, py::arg("database_path"), py::arg("options"),
        py::arg("log"));
  m.def("evaluate", &EvaluateModelPoses, py::arg("model_path"), py::arg("ground_truth"),
        py::arg("format"), py::arg("image_list") = "", py::arg("database_path") = "",
        py::arg("options") = std::map<std::string, std::string>());
}
