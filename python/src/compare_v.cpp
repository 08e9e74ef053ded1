// Comparison of a candidate with a golden image (conformance/compare.h): the rule, profiles,
// percentiles and pass/fail of `oceanref compare`, on EXR files or on arrays.
#include <string>

#include "common.h"
#include "conformance/compare.h"

namespace oceanref::python {

namespace {
using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

// [(part name, {channel: 2-D float32 array})] → parts; every channel of a part the same size.
std::vector<ExrPart> parts_from(const std::string& key, const py::list& spec) {
  std::vector<ExrPart> parts;
  for (const py::handle item : spec) {
    const auto pair = item.cast<py::tuple>();
    ExrPart part;
    part.name = pair[0].cast<std::string>();
    const auto channels = pair[1].cast<py::dict>();
    for (const auto& [name_handle, value] : channels) {
      const std::string name = py::str(name_handle);
      const FloatArray a = FloatArray::ensure(value);
      if (!a || a.ndim() != 2) {
        throw ArgumentError(key, "channel '" + name + "' must be a 2-D array (height, width)");
      }
      const int h = static_cast<int>(a.shape(0));
      const int w = static_cast<int>(a.shape(1));
      if (part.image.channels.empty()) {
        part.image.width = w;
        part.image.height = h;
      } else if (w != part.image.width || h != part.image.height) {
        throw ArgumentError(key, "channel '" + name + "' is " + std::to_string(h) + "x" +
                                     std::to_string(w) + ", the part's other channels " +
                                     std::to_string(part.image.height) + "x" +
                                     std::to_string(part.image.width));
      }
      part.image.channels.push_back({name, 1, std::vector<float>(a.data(), a.data() + a.size())});
    }
    parts.push_back(std::move(part));
  }
  return parts;
}

py::dict percentiles(const std::array<double, 5>& v) {
  py::dict d;
  for (std::size_t i = 0; i < v.size(); ++i) d[kPercentileNames[i]] = v[i];
  return d;
}

py::dict threshold_dict(const ChannelThreshold& t) {
  py::dict d;
  d["abs"] = t.absolute;
  d["rel"] = t.relative;
  d["floor"] = t.floor;
  d["ulp"] = t.ulp;
  d["max_fail_share"] = t.allowed_share;
  return d;
}

py::dict result_dict(const Comparison& c, const std::string& golden, const std::string& candidate) {
  py::dict d;
  d["passed"] = c.pass;
  d["nonfinite_mismatches"] = c.nonfinite_mismatches;
  d["parts_not_compared"] = c.parts_not_compared;
  py::list parts;
  for (const PartResult& p : c.parts) {
    py::dict part;
    part["name"] = p.name;
    part["level"] = py::make_tuple(p.level_x, p.level_y);
    part["passed"] = p.pass;
    part["failing_share"] = p.failing_share;
    part["not_compared"] = p.not_compared;
    py::list channels;
    for (const ChannelResult& r : p.channels) {
      py::dict ch;
      ch["golden"] = r.golden_name;
      ch["candidate"] = r.candidate_name;
      ch["passed"] = r.pass;
      ch["threshold"] = threshold_dict(r.threshold);
      ch["golden_rms"] = r.golden_rms;
      ch["max_absolute"] = r.max_absolute;
      ch["max_relative"] = r.max_relative;
      ch["rmse"] = r.rmse;
      ch["psnr"] = r.psnr;
      ch["max_ulp"] = r.max_ulp;
      ch["absolute_percentiles"] = percentiles(r.absolute_percentiles);
      ch["relative_percentiles"] = percentiles(r.relative_percentiles);
      ch["values"] = r.values;
      ch["failing"] = r.failing;
      ch["failing_share"] = r.failing_share;
      ch["nonfinite_mismatches"] = r.nonfinite_mismatches;
      ch["golden_error_channels"] = r.golden_error_channels;
      channels.append(ch);
    }
    part["channels"] = channels;
    parts.append(part);
  }
  d["parts"] = parts;
  d["text"] = comparison_text(c);
  d["json"] = comparison_json(c, golden, candidate);
  return d;
}
}  // namespace

void bind_compare(py::module_& m) {
  m.def(
      "_compare",
      [](const py::object& candidate, const py::object& golden, const py::object& profile,
         double abs, double rel, double floor, long long ulp, double share,
         const std::string& channels, bool converged, const std::string& candidate_name,
         const std::string& golden_name) {
        const auto load = [](const std::string& key, const py::object& source) {
          if (py::isinstance<py::str>(source)) {
            try {
              return read_parts_for_compare(source.cast<std::string>());
            } catch (const std::exception& e) {
              throw ArgumentError(key, e.what());
            }
          }
          return parts_from(key, source.cast<py::list>());
        };
        const std::vector<ExrPart> c = load("candidate", candidate);
        const std::vector<ExrPart> g = load("golden", golden);
        const auto check = [](const char* key, double v, double hi) {
          if (!(v >= 0.0 && v <= hi)) {
            throw ArgumentError(
                key, "must be in [0, " + format_number(hi) + "], got " + format_number(v));
          }
        };
        check("abs", abs, 1e30);
        check("rel", rel, 1e30);
        check("floor", floor, 1e30);
        check("max_fail_share", share, 1.0);
        if (ulp < 0 || ulp > 4294967296LL) {
          throw ArgumentError("ulp", "must be in [0, 4294967296], got " + std::to_string(ulp));
        }
        ThresholdProfile p = uniform_profile({abs, rel, floor, ulp, share});
        if (!profile.is_none()) {
          try {
            p = read_profile(profile.cast<std::string>());
          } catch (const std::invalid_argument& e) {
            throw ArgumentError("profile", e.what());
          }
        }
        if (converged) p.golden_error = true;
        ChannelSelection selection;
        if (!channels.empty()) {
          try {
            selection = parse_channel_selection(channels);
          } catch (const std::invalid_argument& e) {
            throw ArgumentError("channels", e.what());
          }
        }
        Comparison result;
        try {
          result = compare_parts(g, c, selection, p);
        } catch (const std::invalid_argument& e) {
          throw ArgumentError("compare", e.what());
        }
        return result_dict(result, golden_name, candidate_name);
      },
      py::arg("candidate"), py::arg("golden"), py::arg("profile"), py::arg("abs"), py::arg("rel"),
      py::arg("floor"), py::arg("ulp"), py::arg("max_fail_share"), py::arg("channels"),
      py::arg("converged"), py::arg("candidate_name"), py::arg("golden_name"));
}

}  // namespace oceanref::python
