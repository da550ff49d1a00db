// The Python module `meshvid`: .mvid files opened from a path or bytes, frames decoded to
// numpy arrays, key groups, and encoding of captures held in numpy arrays. Library errors are
// raised as meshvid.Error with the library's message.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstring>
#include <memory>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "codec/dec/mvid_decoder.h"
#include "codec/enc/encoder.h"
#include "format/output_file.h"
#include "meshvid/version.h"

namespace py = pybind11;

namespace meshvid {
namespace {

/// The Python exception every library error becomes.
PyObject* g_error = nullptr;

[[noreturn]] void Raise(const Status& status) {
  PyErr_SetString(g_error, status.message().c_str());
  throw py::error_already_set();
}

template <typename T>
T Unwrap(StatusOr<T> result) {
  if (!result.ok()) Raise(result.status());
  return std::move(*result);
}

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;
using IntArray = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>;

/// (vertices float32 (N, 3), triangles int32 (T, 3)) of a mesh.
py::tuple ToNumpy(const TriangleMesh& mesh) {
  py::array_t<float> vertices({static_cast<py::ssize_t>(mesh.vertex_count()), py::ssize_t{3}});
  py::array_t<std::int32_t> triangles(
      {static_cast<py::ssize_t>(mesh.triangle_count()), py::ssize_t{3}});
  std::memcpy(vertices.mutable_data(), mesh.positions.data(), 12 * mesh.vertex_count());
  std::memcpy(triangles.mutable_data(), mesh.triangles.data(), 12 * mesh.triangle_count());
  return py::make_tuple(vertices, triangles);
}

/// A mesh from numpy arrays (V, 3) and (F, 3); `what` names it in errors.
TriangleMesh FromNumpy(const py::handle& vertices_object, const py::handle& triangles_object,
                       const std::string& what) {
  const FloatArray vertices = FloatArray::ensure(vertices_object);
  const IntArray triangles = IntArray::ensure(triangles_object);
  if (!vertices || vertices.ndim() != 2 || vertices.shape(1) != 3) {
    Raise(InvalidArgumentError(what + ": vertices must be an array of shape (V, 3)"));
  }
  if (!triangles || triangles.ndim() != 2 || triangles.shape(1) != 3) {
    Raise(InvalidArgumentError(what + ": triangles must be an integer array of shape (F, 3)"));
  }
  TriangleMesh mesh;
  mesh.positions.resize(vertices.shape(0));
  std::memcpy(mesh.positions.data(), vertices.data(), 12 * mesh.positions.size());
  mesh.triangles.resize(triangles.shape(0));
  const std::int64_t* t = triangles.data();
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const std::int64_t index = t[3 * i + c];
      if (index < 0 || index >= static_cast<std::int64_t>(mesh.positions.size())) {
        Raise(InvalidArgumentError(what + ": triangle " + std::to_string(i) + " has vertex " +
                                   std::to_string(index) + ", not in 0.." +
                                   std::to_string(mesh.positions.size() - 1)));
      }
      mesh.triangles[i][c] = static_cast<std::uint32_t>(index);
    }
  }
  const Status valid = ValidateMesh(mesh, what);
  if (!valid.ok()) Raise(valid);
  return mesh;
}

/// An opened .mvid; closed by close() or at the end of a `with` block.
class File {
 public:
  File(std::unique_ptr<MvidDecoder> decoder, std::string name)
      : decoder_(std::move(decoder)), name_(std::move(name)) {}

  py::dict Info() const {
    const MvidInfo& info = decoder().info();
    py::dict d;
    d["frame_count"] = info.frame_count;
    d["declared_frame_count"] = info.declared_frame_count;
    d["partial"] = info.partial();
    d["frame_rate"] = info.frame_rate;
    d["levels"] = info.levels;
    d["codec"] = std::string(VideoCodecName(info.codec));
    d["colour"] = info.colour;
    d["gof_size"] = info.gof_size;
    d["format_version"] = info.format_version;
    d["file_bytes"] = info.file_bytes;
    d["vertices_per_level"] = info.vertices_per_level;
    d["triangles_per_level"] = info.triangles_per_level;
    d["key_groups"] = KeyGroups();
    d["metadata"] = Metadata();
    return d;
  }

  /// The file's metadata JSON as a dict (empty if it has none).
  py::object Metadata() const {
    const std::string& text = decoder().info().metadata_json;
    if (text.empty()) return py::dict();
    return py::module_::import("json").attr("loads")(text);
  }

  std::string Repr() const {
    if (!decoder_) return "<meshvid.File " + name_ + " (closed)>";
    const MvidInfo& info = decoder_->info();
    std::ostringstream text;
    text << "<meshvid.File " << name_ << ": " << info.frame_count << " frame"
         << (info.frame_count == 1 ? "" : "s");
    if (info.partial()) text << " of " << info.declared_frame_count << " (partial)";
    text << " at " << info.frame_rate << " fps, " << info.key_groups.size() << " key group"
         << (info.key_groups.size() == 1 ? "" : "s") << ", levels 0.." << info.levels << ", "
         << VideoCodecName(info.codec) << ">";
    return text.str();
  }

  void Close() { decoder_.reset(); }

  /// [(first_frame, frame_count), ...]
  std::vector<std::pair<std::uint32_t, std::uint32_t>> KeyGroups() const {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
    for (const MvidKeyGroupSpan& k : decoder().info().key_groups) {
      out.emplace_back(k.first_frame, k.frame_count);
    }
    return out;
  }

  std::uint32_t KeyGroupOf(std::int64_t frame) {
    return Unwrap(decoder().KeyGroupOf(CheckFrame(frame)));
  }

  py::tuple Frame(std::int64_t frame, int level) {
    const std::uint32_t t = CheckFrame(frame);
    const int l = level < 0 ? decoder().info().levels : level;
    StatusOr<TriangleMesh> mesh = InvalidArgumentError("");
    {
      py::gil_scoped_release release;
      mesh = decoder().DecodeFrame(t, l);
    }
    return ToNumpy(Unwrap(std::move(mesh)));
  }

  /// Vertex colours of frame t at `level` as uint8 (N, 3), in the order of frame()'s vertices.
  py::array_t<std::uint8_t> Colours(std::int64_t frame, int level) {
    const std::uint32_t t = CheckFrame(frame);
    const int l = level < 0 ? decoder().info().levels : level;
    std::vector<Colour> colours;
    Status status;
    {
      py::gil_scoped_release release;
      status = decoder().DecodeColours(t, l, &colours);
    }
    if (!status.ok()) Raise(status);
    static_assert(sizeof(Colour) == 3, "colours are copied as packed bytes");
    py::array_t<std::uint8_t> out({static_cast<py::ssize_t>(colours.size()), py::ssize_t{3}});
    std::memcpy(out.mutable_data(), colours.data(), 3 * colours.size());
    return out;
  }

  std::uint32_t frame_count() const { return decoder().info().frame_count; }

 private:
  /// The decoder; a closed file raises ValueError, as Python's own files do.
  MvidDecoder& decoder() const {
    if (!decoder_) throw py::value_error("I/O operation on a closed meshvid.File (" + name_ + ")");
    return *decoder_;
  }

  std::uint32_t CheckFrame(std::int64_t frame) const {
    if (frame < 0 || frame >= static_cast<std::int64_t>(frame_count())) {
      throw py::index_error("frame " + std::to_string(frame) + " is not in 0.." +
                            std::to_string(static_cast<std::int64_t>(frame_count()) - 1));
    }
    return static_cast<std::uint32_t>(frame);
  }
  std::unique_ptr<MvidDecoder> decoder_;
  std::string name_;  ///< 'path' or "<N bytes>", for repr and errors
};

/// Iterates over a File's frames (holding a reference on it).
struct FrameIterator {
  py::object file;
  int level = -1;
  std::uint32_t next = 0;
};

/// Frames held in memory as the encoder's input.
class ArrayFrameSource : public FrameSource {
 public:
  ArrayFrameSource(std::vector<std::vector<TriangleMesh>> frames, double frame_rate)
      : frames_(std::move(frames)), frame_rate_(frame_rate) {}
  int frame_count() const override { return static_cast<int>(frames_.size()); }
  int view_count() const override { return static_cast<int>(frames_[0].size()); }
  double frame_rate() const override { return frame_rate_; }
  StatusOr<std::vector<TriangleMesh>> LoadFrame(int frame) const override {
    return frames_[frame];
  }

 private:
  std::vector<std::vector<TriangleMesh>> frames_;
  double frame_rate_;
};

py::bytes Encode(const py::sequence& frames, const std::string& path, int quality,
                 const std::string& codec, int levels, double rebase_gain_db, int max_key_groups,
                 double frame_rate, int gof_size, std::size_t base_vertices, int effort,
                 const py::object& progress, const py::object& tune) {
  std::vector<std::vector<TriangleMesh>> meshes;
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const py::sequence views = py::reinterpret_borrow<py::sequence>(frames[f]);
    std::vector<TriangleMesh> frame;
    for (std::size_t v = 0; v < views.size(); ++v) {
      const py::sequence pair = py::reinterpret_borrow<py::sequence>(views[v]);
      const std::string what = "frame " + std::to_string(f) + " view " + std::to_string(v);
      if (pair.size() != 2) Raise(InvalidArgumentError(what + ": expected (vertices, triangles)"));
      frame.push_back(FromNumpy(pair[0], pair[1], what));
    }
    if (frame.empty()) Raise(InvalidArgumentError("frame " + std::to_string(f) + " has no view"));
    if (!meshes.empty() && frame.size() != meshes[0].size()) {
      Raise(InvalidArgumentError("frame " + std::to_string(f) + " has " +
                                 std::to_string(frame.size()) + " views, frame 0 " +
                                 std::to_string(meshes[0].size())));
    }
    meshes.push_back(std::move(frame));
  }
  if (meshes.empty()) Raise(InvalidArgumentError("no frames to encode"));
  EncoderOptions options;
  const std::optional<VideoCodec> video = ParseVideoCodec(codec);
  if (!video) Raise(InvalidArgumentError("unknown codec '" + codec + "' (hevc, av1 or ffv1)"));
  options.codec = *video;
  options.quality = quality;
  options.levels = levels;
  options.rebase_gain_db = rebase_gain_db;
  options.max_key_groups = max_key_groups;
  options.gof_size = gof_size;
  options.base_vertices = base_vertices;
  options.effort = effort;
  // The internals by key, as `meshvid encode --tune KEY=VALUE` sets them (docs/tuning.md).
  if (!tune.is_none()) {
    for (const auto& [key, value] : py::cast<py::dict>(tune)) {
      const std::string text = py::isinstance<py::bool_>(value)
                                   ? (value.cast<bool>() ? "true" : "false")
                                   : py::str(value).cast<std::string>();
      const Status set = SetTuning(options.tuning, py::str(key).cast<std::string>(), text);
      if (!set.ok()) Raise(set);
    }
  }
  options.metadata_json = R"({"encoder":"meshvid python"})";
  ArrayFrameSource source(std::move(meshes), frame_rate);
  std::ostringstream out;
  // Runs without the GIL; takes it to call `progress` and to see Ctrl-C, either of which
  // stops the encoder (a raised exception is re-raised after it has stopped).
  bool interrupted = false;
  const ProgressCallback callback = [&](std::string_view stage, long done, long total) {
    py::gil_scoped_acquire acquire;
    if (PyErr_CheckSignals() != 0) {
      interrupted = true;
      return false;
    }
    if (progress.is_none()) return true;
    try {
      const py::object answer = progress(std::string(stage), done, total);
      return answer.is_none() || answer.cast<bool>();
    } catch (py::error_already_set& e) {
      e.restore();
      interrupted = true;
      return false;
    }
  };
  StatusOr<EncodeSummary> summary = InvalidArgumentError("");
  {
    py::gil_scoped_release release;
    summary = EncodeCapture(source, OstreamSink(out), options, callback);
  }
  if (interrupted && PyErr_Occurred() != nullptr) throw py::error_already_set();
  if (!summary.ok()) Raise(summary.status());
  const std::string bytes = out.str();
  if (!path.empty()) {
    const Status written = WriteFileAtomically(path, bytes);
    if (!written.ok()) Raise(written);
  }
  return py::bytes(bytes);
}

}  // namespace
}  // namespace meshvid

PYBIND11_MODULE(meshvid, m) {
  using namespace meshvid;
  m.doc() = "meshvid: codec and file format for captured dynamic 3D surfaces (.mvid).";
  m.attr("__version__") = MESHVID_VERSION_STRING;
  static py::exception<std::runtime_error> error(m, "Error");
  g_error = error.ptr();

  py::class_<FrameIterator>(m, "FrameIterator", "Frames of a File, decoded one at a time.")
      .def("__iter__", [](FrameIterator& it) -> FrameIterator& { return it; })
      .def("__next__", [](FrameIterator& it) {
        File& file = it.file.cast<File&>();
        if (it.next >= file.frame_count()) throw py::stop_iteration();
        return file.Frame(it.next++, it.level);
      });

  py::class_<File>(m, "File", "An opened .mvid file (see meshvid.open).")
      .def_property_readonly("info", &File::Info,
                             "dict: frame_count, declared_frame_count (the header's), partial, "
                             "frame_rate, levels, codec, key_groups, vertices_per_level and "
                             "triangles_per_level (of key group 0), metadata, ...")
      .def_property_readonly("metadata", &File::Metadata,
                             "dict: what the encoder recorded (encoder, capture, ...)")
      .def_property_readonly(
          "partial", [](const File& f) { return f.Info()["partial"]; },
          "True if the file is cut or damaged: fewer frames are readable "
          "than its header promises (opened with allow_partial=True)")
      .def_property_readonly("key_groups", &File::KeyGroups,
                             "[(first_frame, frame_count)]: runs of frames with one "
                             "connectivity")
      .def("key_group_of", &File::KeyGroupOf, py::arg("t"), "The key group holding frame t.")
      .def("frame", &File::Frame, py::arg("t"), py::arg("level") = -1,
           "(vertices float32 (N, 3), triangles int32 (T, 3)) of frame t at `level` "
           "(-1: the finest stored). Frames of one key group share the triangles.")
      .def("colours", &File::Colours, py::arg("t"), py::arg("level") = -1,
           "Vertex colours uint8 (N, 3) of frame t at `level`, in frame()'s vertex order; "
           "meshvid.Error if the file has no colour (info['colour']).")
      .def(
          "frames",
          [](py::object self, int level) {
            return FrameIterator{self, level};
          },
          py::arg("level") = -1,
          "An iterator over every frame at `level`, decoding one frame per step.")
      .def("__len__", &File::frame_count)
      .def("__repr__", &File::Repr)
      .def("close", &File::Close, "Releases the file; later calls raise ValueError.")
      .def("__enter__", [](py::object self) { return self; })
      .def("__exit__",
           [](File& f, const py::object&, const py::object&, const py::object&) {
             f.Close();
             return false;
           })
      .def(
          "__iter__",
          [](py::object self) {
            return FrameIterator{self, -1};
          },
          "Iterates over the frames at the finest level, decoding one per step.");

  m.def(
      "open",
      [](py::object source, bool allow_partial) {
        MvidDecoderOptions options;
        options.allow_partial = allow_partial;
        std::unique_ptr<MvidDecoder> decoder;
        std::string name;
        if (py::isinstance<py::bytes>(source) || py::isinstance<py::bytearray>(source) ||
            py::isinstance<py::memoryview>(source)) {
          const std::string bytes = py::bytes(source);
          decoder = Unwrap(MvidDecoder::OpenMemory(
              std::vector<std::uint8_t>(bytes.begin(), bytes.end()), options));
          name = "<" + std::to_string(bytes.size()) + " bytes>";
        } else {
          const std::string path = py::str(py::module_::import("os").attr("fspath")(source));
          decoder = Unwrap(MvidDecoder::OpenFile(path, options));
          name = py::repr(py::str(path));
        }
        if (decoder->info().partial()) {
          const std::string warning = name + ": " + PartialFileText(decoder->info());
          PyErr_WarnEx(PyExc_UserWarning, warning.c_str(), 1);
        }
        return File(std::move(decoder), name);
      },
      py::arg("source"), py::arg("allow_partial") = false,
      "Opens a .mvid from a path or from bytes; usable in a `with` block. A cut or damaged "
      "file (fewer frames readable than its header promises) raises meshvid.Error, unless "
      "allow_partial=True: then it opens with a UserWarning and File.partial is True.");

  // The defaults are EncoderOptions' own, as `meshvid encode`'s are.
  const EncoderOptions defaults;
  m.def("encode", &Encode, py::arg("frames"), py::arg("path") = "",
        py::arg("quality") = defaults.quality,
        py::arg("codec") = std::string(VideoCodecName(defaults.codec)),
        py::arg("levels") = defaults.levels, py::arg("rebase_gain_db") = defaults.rebase_gain_db,
        py::arg("max_key_groups") = defaults.max_key_groups, py::arg("frame_rate") = 25.0,
        py::arg("gof_size") = defaults.gof_size, py::arg("base_vertices") = defaults.base_vertices,
        py::arg("effort") = defaults.effort, py::arg("progress") = py::none(),
        py::arg("tune") = py::none(),
        "Encodes a capture: `frames` is a list of frames, each a list of views "
        "(vertices (V, 3), triangles (F, 3)) in world coordinates. Returns the .mvid bytes "
        "(also written to `path` if given). Options as `meshvid encode`'s; `tune`, a dict of "
        "the encoder's internals by key (docs/tuning.md), as its --tune. `progress`, if "
        "given, is called as progress(stage, done, total); returning False cancels "
        "(meshvid.Error). Ctrl-C interrupts.");
}
