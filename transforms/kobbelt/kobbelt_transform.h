#pragma once
// Kobbelt-Schroder variational subdivision wavelets as a pupwave::Transform1D.
//
// Analysis is S^{-1} = (U_e^T ; C) (Eq. 18): the coarse band is the even samples and the
// detail band is C p, each row normalised so that detail = odd sample minus its variational
// prediction (the FIR dual side). Synthesis runs the subdivision wiring diagram (Fig. 12):
// predict-odd with -B, then the cyclic-reduction lifting network for A^{-1}. The stabilised
// variants add the lifting step of Eq. (19) with V from Table 1 (coarse += V detail in
// analysis), giving the primal wavelets 4 vanishing moments. Details of constants vanish,
// so the coarse band has DC gain 1 in every variant. Finite lines use natural boundaries
// (see variational.h); V taps that would fall outside the coarse band are folded onto the
// nearest coarse sample, which keeps every column sum of V (the zeroth moment).

#include <string>
#include <string_view>
#include <vector>

#include "transforms/kobbelt/variational.h"
#include "transforms/transform1d.h"

namespace pupwave {

// body: "k2", "k3", "kspl", "k4pt" (stabilised with V) or "k2-raw", "k3-raw", "kspl-raw",
// "k4pt-raw" (no V step). std::invalid_argument listing the valid names otherwise.
// spec() of the result is "kobbelt:" + body.
Transform1DPtr make_kobbelt_transform_from_spec(std::string_view body);

// Every valid full spec string: "kobbelt:k2", ..., "kobbelt:k4pt-raw".
std::vector<std::string> kobbelt_transform_specs();

namespace kobbelt {

// Table 1: the four taps of one column of V for `scheme` (on coarse j-1 .. j+2 of detail j).
std::vector<double> stabilizing_weights(Scheme scheme);

}  // namespace kobbelt
}  // namespace pupwave
