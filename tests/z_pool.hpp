#pragma once
// Readings with standard errors judged against references, pooled: each z = (value -
// reference) / sigma within z_max, and their mean square near 1 (chi-square with K degrees
// of freedom over K, within z_max sqrt(2/K)). `check` prints the figure with a tag, as the
// validation documents quote it.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>

namespace luxtrace::test_support {

class ZPool {
public:
    explicit ZPool(std::string tag, double z_max = 5.0) : tag_(std::move(tag)), z_max_(z_max) {}

    void add(const std::string& what, double value, double sigma, double reference) {
        const double z = (value - reference) / sigma;
        EXPECT_LT(std::abs(z), z_max_) << what << ": " << value << " +- " << sigma << ", reference " << reference;
        sum_z2_ += z * z;
        ++count_;
    }
    // Any reading with `value` and `sigma` members.
    template <class R>
    void add(const std::string& what, const R& r, double reference) {
        add(what, r.value, r.sigma, reference);
    }
    void check(const std::string& what) const {
        const double mean = sum_z2_ / count_, band = z_max_ * std::sqrt(2.0 / count_);
        EXPECT_NEAR(mean, 1.0, band) << what << ": mean z^2 over " << count_ << " readings";
        std::cout << "[" << tag_ << "] " << what << ": " << count_ << " readings, mean z^2 " << mean
                  << " (allowed 1 +- " << band << ")\n";
    }

private:
    std::string tag_;
    double z_max_;
    double sum_z2_ = 0.0;
    int count_ = 0;
};

}  // namespace luxtrace::test_support
