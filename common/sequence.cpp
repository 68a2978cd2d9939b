#include "common/sequence.hpp"

#include "common/file_util.hpp"
#include "common/json_io.hpp"

#include <opencv2/imgcodecs.hpp>

#include <array>
#include <cinttypes>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace stairs {
namespace fs = std::filesystem;

namespace {

// Calls f(line stream, "FILE:LINE: ") for each line of a text file that is
// neither blank nor a '#' comment.
template <class F>
void for_each_data_line(std::istream& in, const std::string& path, F f) {
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream ls(line);
    f(ls, path + ":" + std::to_string(line_no) + ": ");
  }
}

// Timestamps beyond this (about 3000 years) are garbage: their utime would overflow int64.
constexpr double kMaxTimestamp_s = 1e11;

int64_t utime_of(double timestamp_s) {
  return static_cast<int64_t>(timestamp_s * 1e6 + (timestamp_s >= 0 ? 0.5 : -0.5));
}

// A timestamped text file of N numbers per line after the timestamp ('#'
// comments, blank lines): make(utime, values, where) builds a sample (throwing
// with `where` = "FILE:LINE: " on a bad one); time must increase.
template <size_t N, class Sample, class Make>
std::vector<Sample> read_timestamped(const std::string& path, const char* format, Make make) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": unreadable");
  std::vector<Sample> out;
  for_each_data_line(in, path, [&](std::istringstream& ls, const std::string& where) {
    double t = 0;
    std::array<double, N> v{};
    bool ok = static_cast<bool>(ls >> t);
    for (double& x : v) ok = ok && static_cast<bool>(ls >> x) && std::isfinite(x);
    ok = ok && std::abs(t) < kMaxTimestamp_s;  // a utime in us must fit in int64
    if (!ok) throw std::runtime_error(where + "expected '<timestamp_s> " + format + "' (finite numbers)");
    Sample s = make(utime_of(t), v, where);
    if (!out.empty() && s.utime <= out.back().utime) throw std::runtime_error(where + "time does not increase");
    out.push_back(s);
  });
  return out;
}

}  // namespace

SequenceReader::SequenceReader(const std::string& dir) : dir_(dir) {
  if (!fs::is_directory(dir)) throw std::runtime_error(dir + ": not a directory");
  const std::string camera = (fs::path(dir) / "camera.json").string();
  if (!fs::exists(camera)) throw std::runtime_error(camera + ": missing");
  intrinsics_from_json(read_json_file(camera), camera, K_, depth_scale_);
  // A 16-bit depth PNG spans 0.1 mm to 1 cm per unit in practice (TUM 0.0002, Kinect 0.001); a
  // scale outside that is most likely a unit mistake (1.0 puts every point beyond any sensor's range).
  if (depth_scale_ < 1e-5 || depth_scale_ > 0.01)
    warnings_.push_back(camera + ": depth_scale " + std::to_string(depth_scale_) +
                        " m per unit is implausible (expected 0.0001-0.01: 0.001 for millimetres)");

  const std::string index = (fs::path(dir) / "depth.txt").string();
  std::ifstream in(index);
  if (!in) throw std::runtime_error(index + ": missing or unreadable");
  for_each_data_line(in, index, [&](std::istringstream& ls, const std::string& where) {
    Entry e;
    if (!(ls >> e.timestamp >> e.path) || !(std::abs(e.timestamp) < kMaxTimestamp_s))
      throw std::runtime_error(where + "expected '<timestamp_s> <path.png>' (a finite timestamp)");
    entries_.push_back(e);
  });
  if (entries_.empty()) throw std::runtime_error(index + ": lists no frames");

  const std::string gt = (fs::path(dir) / "groundtruth.json").string();
  if (fs::exists(gt)) ground_truth_ = ground_truth_from_json(read_json_file(gt), gt);
  const auto optional_file = [&](const char* name, auto read, auto& out) {
    const std::string path = (fs::path(dir) / name).string();
    if (!fs::exists(path)) return;
    try {
      out = read(path);
    } catch (const std::runtime_error& e) {
      warnings_.push_back(std::string(e.what()) + " (" + name + " left out)");
    }
  };
  optional_file("odometry.txt", read_odometry_file, odometry_);
  optional_file("imu.txt", read_imu_file, imu_);
}

std::vector<ImuSample> read_imu_file(const std::string& path) {
  return read_timestamped<6, ImuSample>(path, "ax ay az gx gy gz", [](int64_t utime, const auto& v, const std::string&) {
    ImuSample s;
    s.utime = utime;
    s.specific_force_mps2 = Eigen::Vector3d(v[0], v[1], v[2]);
    s.angular_rate_radps = Eigen::Vector3d(v[3], v[4], v[5]);
    return s;
  });
}

std::vector<OdometrySample> read_odometry_file(const std::string& path) {
  return read_timestamped<7, OdometrySample>(
      path, "x y z qw qx qy qz", [](int64_t utime, const auto& v, const std::string& where) {
        const Eigen::Quaterniond q(v[3], v[4], v[5], v[6]);
        if (std::abs(q.norm() - 1.0) > 1e-3) throw std::runtime_error(where + "qw qx qy qz is no unit quaternion");
        OdometrySample o;
        o.utime = utime;
        o.position_m = Eigen::Vector3d(v[0], v[1], v[2]);
        o.orientation = q.normalized();
        return o;
      });
}

DepthImage SequenceReader::read(size_t i) const {
  const Entry& e = entries_.at(i);
  const std::string path = (fs::path(dir_) / e.path).string();
  if (!fs::exists(path)) throw std::runtime_error(path + ": missing (listed in depth.txt)");
  cv::Mat m = cv::imread(path, cv::IMREAD_ANYDEPTH | cv::IMREAD_GRAYSCALE);
  if (m.empty()) throw std::runtime_error(path + ": not a readable image");
  if (m.depth() != CV_16U)
    throw std::runtime_error(path + ": depth PNG must be 16-bit unsigned, found " +
                             (m.depth() == CV_8U ? std::string("8-bit") : std::string("another type")));
  if (m.cols != K_.width || m.rows != K_.height)
    throw std::runtime_error(path + ": size " + std::to_string(m.cols) + "x" + std::to_string(m.rows) +
                             " does not match camera.json " + std::to_string(K_.width) + "x" +
                             std::to_string(K_.height));
  DepthImage img;
  img.K = K_;
  img.depth_scale = depth_scale_;
  img.depth.resize(static_cast<size_t>(K_.width) * K_.height);
  for (int v = 0; v < m.rows; ++v)
    std::memcpy(img.depth.data() + static_cast<size_t>(v) * K_.width, m.ptr<uint16_t>(v),
                sizeof(uint16_t) * K_.width);
  img.utime = utime_of(e.timestamp);
  img.seq = static_cast<int32_t>(i);
  return img;
}

SequenceWriter::SequenceWriter(const std::string& dir, const Intrinsics& K, double depth_scale)
    : dir_(dir), K_(K), depth_scale_(depth_scale) {
  make_directories((fs::path(dir) / "depth").string());
  // A stale index from an earlier run would make this one look complete early.
  fs::remove(fs::path(dir) / "depth.txt");
  fs::remove(fs::path(dir) / "odometry.txt");
  fs::remove(fs::path(dir) / "imu.txt");
  index_ = "# depth maps: uint16 PNG, depth along the optical axis, 0 = no measurement\n"
           "# timestamp filename\n";
}

void SequenceWriter::write(const DepthImage& img, double timestamp_s) {
  if (img.K.width != K_.width || img.K.height != K_.height)
    throw std::runtime_error(dir_ + ": frame size differs from the sequence's camera");
  char name[32];
  std::snprintf(name, sizeof(name), "depth/%06zu.png", count_++);
  const cv::Mat m = cv::Mat(K_.height, K_.width, CV_16UC1, const_cast<uint16_t*>(img.depth.data()));
  const std::string path = (fs::path(dir_) / name).string();
  if (!cv::imwrite(path, m, {cv::IMWRITE_PNG_COMPRESSION, 1}))
    throw std::runtime_error(path + ": cannot write PNG");
  char line[96];
  std::snprintf(line, sizeof(line), "%.6f %s\n", timestamp_s, name);
  index_ += line;
}

void SequenceWriter::write_odometry(const OdometrySample& o) {
  if (odometry_.empty()) odometry_ = "# camera optical frame in a drifting odometry frame (z up), m\n# timestamp_s x y z qw qx qy qz\n";
  const Eigen::Quaterniond& q = o.orientation;
  char line[224];
  std::snprintf(line, sizeof(line), "%.6f %.6f %.6f %.6f %.9f %.9f %.9f %.9f\n", o.utime * 1e-6, o.position_m.x(),
                o.position_m.y(), o.position_m.z(), q.w(), q.x(), q.y(), q.z());
  odometry_ += line;
}

void SequenceWriter::write_imu(const ImuSample& s) {
  if (imu_.empty()) imu_ = "# specific force (m/s^2) and angular rate (rad/s) in the camera optical frame\n# timestamp_s ax ay az gx gy gz\n";
  char line[224];
  std::snprintf(line, sizeof(line), "%.6f %.6f %.6f %.6f %.7f %.7f %.7f\n", s.utime * 1e-6, s.specific_force_mps2.x(),
                s.specific_force_mps2.y(), s.specific_force_mps2.z(), s.angular_rate_radps.x(),
                s.angular_rate_radps.y(), s.angular_rate_radps.z());
  imu_ += line;
}

void SequenceWriter::finish(const std::optional<GroundTruth>& ground_truth) {
  write_json_file((fs::path(dir_) / "camera.json").string(), to_json(K_, depth_scale_));
  if (!odometry_.empty()) write_file_atomically((fs::path(dir_) / "odometry.txt").string(), odometry_);
  if (!imu_.empty()) write_file_atomically((fs::path(dir_) / "imu.txt").string(), imu_);
  if (ground_truth) write_json_file((fs::path(dir_) / "groundtruth.json").string(), to_json(*ground_truth));
  write_file_atomically((fs::path(dir_) / "depth.txt").string(), index_);
}

}  // namespace stairs
