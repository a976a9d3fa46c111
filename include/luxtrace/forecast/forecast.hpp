#pragma once
// Forecast of the photons and wall time a target needs (eqs. 10-11): statistical errors
// fall as 1/sqrt(N), counts of received photons grow as N. Pure functions of the
// reduced history.
#include <vector>

namespace luxtrace {

struct HistoryPoint {
    double time_s = 0.0;
    double photons = 0.0;
    double value = 0.0;  // the target's error (or received count) at that reduction
};

struct Forecast {
    bool valid = false;
    double photons_needed = 0.0;  // total photons at which the goal is reached
    double time_s = 0.0;          // wall time (since the run's start) at which it is reached
    double exponent = 0.5;        // alpha of sigma = C / N^alpha used
};

// Photon rate from (time, photons) points of one part of a run: least-squares slope
// over the later half of the points (start-up excluded).
double photon_rate(const std::vector<HistoryPoint>& points);

// Error target: fits value = C / sqrt(N) to the points with N >= N_last / 10, weighting
// later points more (weights N), then solves C / sqrt(N) = goal; the wall time follows
// at `rate` photons per second from the last point.
Forecast forecast_error(const std::vector<HistoryPoint>& history, double goal, double rate);

// The same with the exponent fitted, for QMC (docs/QMC.md), whose error falls faster than
// 1/sqrt(N) where the integrand allows: least squares of log sigma = log C - alpha log N
// over the same points and weights, alpha floored at 1/2 (never forecast slower than
// Monte Carlo) and taken as 1/2 until the points span a factor 4 in N (three at least).
Forecast forecast_error_fitted(const std::vector<HistoryPoint>& history, double goal, double rate);

// Count target: fits value = a N (through the origin) and solves a N = goal.
Forecast forecast_count(const std::vector<HistoryPoint>& history, double goal, double rate);

}  // namespace luxtrace
