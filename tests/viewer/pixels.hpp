// Pixel classification shared by the viewer tests.
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>

namespace stairs::viewer::test {

// Green clearly dominant: the tread colour (pure or blended over the depth map).
inline bool tread_tinted(const cv::Vec3b& p) { return p[1] > std::max(p[0], p[2]) + 25; }
// Blue clearly dominant: the riser colour.
inline bool riser_tinted(const cv::Vec3b& p) { return p[0] > std::max(p[1], p[2]) + 40 && p[0] > 150; }
// Red clearly dominant: the convex-edge colour.
inline bool convex_red(const cv::Vec3b& p) { return p[2] > 200 && p[1] < 90 && p[0] < 90; }

template <class Pred>
int count_pixels(const cv::Mat& img, Pred pred) {
  int n = 0;
  for (int v = 0; v < img.rows; ++v)
    for (int u = 0; u < img.cols; ++u) n += pred(img.at<cv::Vec3b>(v, u));
  return n;
}

// Risers of a model profile, counted as separate blobs of the riser colour
// (blobs under 8 px are anti-aliasing, not risers).
inline int riser_blobs(const cv::Mat& img) {
  cv::Mat mask(img.size(), CV_8UC1, cv::Scalar(0));
  for (int v = 0; v < img.rows; ++v)
    for (int u = 0; u < img.cols; ++u) mask.at<uint8_t>(v, u) = riser_tinted(img.at<cv::Vec3b>(v, u)) ? 255 : 0;
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8);
  int blobs = 0;
  for (int i = 1; i < n; ++i) blobs += stats.at<int>(i, cv::CC_STAT_AREA) >= 8;
  return blobs;
}

}  // namespace stairs::viewer::test
