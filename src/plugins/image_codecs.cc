// The plug-in util/image_codecs.h loads on first use: OpenCV's imgcodecs behind two C entry points,
// so that only the commands that read or write images pay for its libraries. Exceptions stay on
// this side: OpenCV's are reported as failures, which the callers turn into messages naming the
// file.
#include <opencv2/imgcodecs.hpp>
#include <vector>

extern "C" {

__attribute__((visibility("default"))) bool ramap_read_image(const char* path, int flags,
                                                             cv::Mat* image) {
  try {
    *image = cv::imread(path, flags);
    return !image->empty();
  } catch (const cv::Exception&) {
    return false;
  }
}

__attribute__((visibility("default"))) bool ramap_encode_image(const char* extension,
                                                               const cv::Mat* image,
                                                               std::vector<uchar>* bytes) {
  try {
    return cv::imencode(extension, *image, *bytes);
  } catch (const cv::Exception&) {
    return false;
  }
}
}
