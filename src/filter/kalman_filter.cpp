#include "meridian/filter/kalman_filter.hpp"

namespace meridian::filter {

// The dynamic-size filter, compiled once (extern template in the header).
template class KalmanFilter<Eigen::Dynamic>;

}  // namespace meridian::filter
