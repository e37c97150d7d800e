#include "core/scene/gltf_animation.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/base/error.h"
#include "core/base/log.h"
#include "core/scene/gltf_accessor.h"

namespace prism {

namespace {

template <size_t N>
std::array<double, N> checked(const std::vector<double>& v, std::array<double, N> fallback, const char* what,
                              const std::string& context) {
  if (v.empty()) return fallback;
  if (v.size() != N || !std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); }))
    fail("{}: {} must be {} finite numbers", context, what, N);
  std::copy(v.begin(), v.end(), fallback.begin());
  return fallback;
}

size_t morph_target_count(const tinygltf::Model& model, int mesh) {
  if (mesh < 0 || size_t(mesh) >= model.meshes.size() || model.meshes[mesh].primitives.empty()) return 0;
  return model.meshes[mesh].primitives[0].targets.size();
}

// Spherical linear interpolation along the shorter arc (glTF 2.0 Appendix C).
std::vector<double> slerp(const float* a, const float* b, double s) {
  double d = 0;
  for (int i = 0; i < 4; ++i) d += double(a[i]) * b[i];
  const double sign = d < 0 ? -1 : 1;
  d = std::abs(d);
  double wa = 1 - s, wb = s;  // nearly parallel: linear, normalised below
  if (d < 1 - 1e-6) {
    const double angle = std::acos(d);
    wa = std::sin((1 - s) * angle) / std::sin(angle);
    wb = std::sin(s * angle) / std::sin(angle);
  }
  std::vector<double> q(4);
  for (int i = 0; i < 4; ++i) q[i] = wa * a[i] + sign * wb * b[i];
  return q;
}

void normalize(std::vector<double>& q) {
  double n = 0;
  for (double x : q) n += x * x;
  if (n > 0)
    for (double& x : q) x /= std::sqrt(n);
}

}  // namespace

Transform NodePose::local() const {
  if (matrix) return *matrix;
  return Transform::translate({translation[0], translation[1], translation[2]}) *
         Transform::rotate(rotation[0], rotation[1], rotation[2], rotation[3]) *
         Transform::scale({scale[0], scale[1], scale[2]});
}

std::vector<NodePose> rest_pose(const tinygltf::Model& model, const std::string& file) {
  std::vector<NodePose> pose(model.nodes.size());
  for (size_t i = 0; i < model.nodes.size(); ++i) {
    const tinygltf::Node& node = model.nodes[i];
    const std::string context = fmt::format("{}: node {} '{}'", file, i, node.name);
    NodePose& p = pose[i];
    if (!node.matrix.empty()) {
      const auto m = checked<16>(node.matrix, {}, "matrix", context);
      p.matrix = Transform::from_column_major(m.data());
    }
    p.translation = checked<3>(node.translation, p.translation, "translation", context);
    p.rotation = checked<4>(node.rotation, p.rotation, "rotation", context);
    p.scale = checked<3>(node.scale, p.scale, "scale", context);
    const size_t targets = morph_target_count(model, node.mesh);
    const auto& weights = !node.weights.empty() ? node.weights
                          : targets > 0         ? model.meshes[node.mesh].weights
                                                : node.weights;
    p.weights.assign(targets, 0.0);
    for (size_t k = 0; k < std::min(targets, weights.size()); ++k)
      p.weights[k] = std::isfinite(weights[k]) ? weights[k] : 0.0;
  }
  return pose;
}

std::vector<Animation> read_animations(const tinygltf::Model& model, const std::string& file) {
  std::vector<Animation> animations;
  for (size_t a = 0; a < model.animations.size(); ++a) {
    const tinygltf::Animation& in = model.animations[a];
    const std::string context = fmt::format("{}: animation {} '{}'", file, a, in.name);
    Animation out;
    out.name = in.name;
    out.start = INFINITY;
    out.end = -INFINITY;
    out.samplers.resize(in.samplers.size());
    std::vector<bool> read(in.samplers.size(), false);
    for (size_t c = 0; c < in.channels.size(); ++c) {
      const tinygltf::AnimationChannel& ch = in.channels[c];
      const std::string where = fmt::format("{} channel {}", context, c);
      AnimationChannel channel;
      if (ch.target_path == "translation")
        channel.path = AnimationChannel::Path::translation;
      else if (ch.target_path == "rotation")
        channel.path = AnimationChannel::Path::rotation;
      else if (ch.target_path == "scale")
        channel.path = AnimationChannel::Path::scale;
      else if (ch.target_path == "weights")
        channel.path = AnimationChannel::Path::weights;
      else {
        log::warn("{}: ignoring its target path '{}'", where, ch.target_path);
        continue;
      }
      if (ch.target_node < 0) continue;  // targets something an extension names
      if (size_t(ch.target_node) >= model.nodes.size())
        fail("{}: targets node {}, which does not exist", where, ch.target_node);
      if (ch.sampler < 0 || size_t(ch.sampler) >= in.samplers.size())
        fail("{}: refers to sampler {}, which does not exist", where, ch.sampler);
      channel.node = ch.target_node;
      channel.sampler = ch.sampler;
      const int width = channel.path == AnimationChannel::Path::rotation ? 4
                        : channel.path == AnimationChannel::Path::weights
                            ? int(morph_target_count(model, model.nodes[channel.node].mesh))
                            : 3;
      if (width == 0) fail("{}: animates the morph weights of a node without morph targets", where);
      AnimationSampler& s = out.samplers[ch.sampler];
      if (read[ch.sampler]) {
        if (s.width != width) fail("{}: its sampler is shared by channels of different widths", where);
      } else {
        read[ch.sampler] = true;
        const tinygltf::AnimationSampler& si = in.samplers[ch.sampler];
        const std::string sampler_context = fmt::format("{} sampler {}", context, ch.sampler);
        s.width = width;
        if (si.interpolation == "STEP")
          s.interpolation = Interpolation::step;
        else if (si.interpolation == "CUBICSPLINE")
          s.interpolation = Interpolation::cubic_spline;
        else if (si.interpolation == "LINEAR" || si.interpolation.empty())
          s.interpolation = Interpolation::linear;
        else
          fail("{}: unknown interpolation '{}'", sampler_context, si.interpolation);
        s.times = read_accessor_floats(model, si.input, 1, sampler_context + " input");
        if (s.times.empty()) fail("{} input: no keyframes", sampler_context);
        for (size_t k = 0; k < s.times.size(); ++k)
          if (!std::isfinite(s.times[k]) || (k > 0 && s.times[k] < s.times[k - 1]))
            fail("{} input: key times must be finite and increasing (key {})", sampler_context, k);
        const int components = accessor_components(model, si.output, sampler_context + " output");
        s.values = read_accessor_floats(model, si.output, components, sampler_context + " output");
        const size_t per_key = size_t(width) * (s.interpolation == Interpolation::cubic_spline ? 3 : 1);
        if (s.values.size() != s.times.size() * per_key)
          fail("{} output: {} values for {} keys of {} each", sampler_context, s.values.size(), s.times.size(),
               per_key);
        for (float v : s.values)
          if (!std::isfinite(v)) fail("{} output: values must be finite", sampler_context);
        out.start = std::min(out.start, double(s.times.front()));
        out.end = std::max(out.end, double(s.times.back()));
      }
      out.channels.push_back(channel);
    }
    if (out.channels.empty()) out.start = out.end = 0;
    animations.push_back(std::move(out));
  }
  return animations;
}

int find_animation(const std::vector<Animation>& animations, const std::string& name_or_index,
                   const std::string& file) {
  for (size_t i = 0; i < animations.size(); ++i)
    if (animations[i].name == name_or_index) return int(i);
  const bool digits = !name_or_index.empty() && std::all_of(name_or_index.begin(), name_or_index.end(),
                                                            [](char c) { return c >= '0' && c <= '9'; });
  if (digits && name_or_index.size() < 9 && size_t(std::stoi(name_or_index)) < animations.size())
    return std::stoi(name_or_index);
  std::string list;
  for (size_t i = 0; i < animations.size(); ++i) list += fmt::format("{}{} '{}'", i ? ", " : "", i, animations[i].name);
  fail("{}: no animation '{}' (the file has {})", file, name_or_index, animations.empty() ? "none" : list);
}

std::vector<double> sample(const AnimationSampler& s, double time, bool quaternion) {
  const size_t n = s.times.size(), w = size_t(s.width);
  const bool cubic = s.interpolation == Interpolation::cubic_spline;
  // Key k's value, or (cubic) its in-tangent (slot 0) or out-tangent (slot 2).
  const auto key = [&](size_t k, size_t slot) { return &s.values[cubic ? (3 * k + slot) * w : k * w]; };
  std::vector<double> out(w);
  const auto copy = [&](const float* v) {
    std::copy(v, v + w, out.begin());
    return out;
  };
  if (n == 1 || time <= s.times[0]) return copy(key(0, 1));
  if (time >= s.times[n - 1]) return copy(key(n - 1, 1));
  const size_t k = size_t(std::upper_bound(s.times.begin(), s.times.end(), time) - s.times.begin()) - 1;
  const double td = double(s.times[k + 1]) - s.times[k];
  const double t = td > 0 ? (time - s.times[k]) / td : 0;
  switch (s.interpolation) {
    case Interpolation::step:
      return copy(key(k, 1));
    case Interpolation::linear:
      if (quaternion) return slerp(key(k, 1), key(k + 1, 1), t);
      for (size_t i = 0; i < w; ++i) out[i] = (1 - t) * key(k, 1)[i] + t * key(k + 1, 1)[i];
      return out;
    case Interpolation::cubic_spline: {
      // Hermite basis (Appendix C): p = (2t³−3t²+1) v_k + td (t³−2t²+t) b_k + (−2t³+3t²) v_k+1
      //                                 + td (t³−t²) a_k+1
      const double t2 = t * t, t3 = t2 * t;
      const double h00 = 2 * t3 - 3 * t2 + 1, h10 = t3 - 2 * t2 + t, h01 = -2 * t3 + 3 * t2, h11 = t3 - t2;
      for (size_t i = 0; i < w; ++i)
        out[i] = h00 * key(k, 1)[i] + td * h10 * key(k, 2)[i] + h01 * key(k + 1, 1)[i] + td * h11 * key(k + 1, 0)[i];
      if (quaternion) normalize(out);
      return out;
    }
  }
  return out;
}

void animate(const Animation& animation, double time, std::vector<NodePose>& pose) {
  using Path = AnimationChannel::Path;
  for (const AnimationChannel& c : animation.channels) {
    const std::vector<double> v = sample(animation.samplers[c.sampler], time, c.path == Path::rotation);
    NodePose& p = pose[c.node];
    switch (c.path) {
      case Path::translation:
        std::copy(v.begin(), v.end(), p.translation.begin());
        break;
      case Path::rotation:
        std::copy(v.begin(), v.end(), p.rotation.begin());
        break;
      case Path::scale:
        std::copy(v.begin(), v.end(), p.scale.begin());
        break;
      case Path::weights:
        p.weights = v;
        break;
    }
  }
}

void warn_of_shared_targets(const std::vector<Animation>& animations, const tinygltf::Model& model,
                            const std::string& file) {
  static constexpr const char* kPath[] = {"translation", "rotation", "scale", "weights"};
  std::map<std::pair<int, AnimationChannel::Path>, size_t> driver;  // the first animation that drives each
  size_t shared = 0;
  std::string first;
  for (size_t a = 0; a < animations.size(); ++a)
    for (const AnimationChannel& c : animations[a].channels) {
      const auto [it, added] = driver.try_emplace({c.node, c.path}, a);
      if (added || it->second == a) continue;
      if (shared++ == 0)
        first = fmt::format("'{}' and '{}' both set node {} ('{}') {}", animations[it->second].name, animations[a].name,
                            c.node, model.nodes[size_t(c.node)].name, kPath[int(c.path)]);
    }
  if (shared > 0)
    log::warn("{}: animations {}{}: played together, the later one wins (choose one with --animation)", file, first,
              shared > 1 ? fmt::format(", and {} more such channels", shared - 1) : "");
}

}  // namespace prism
