# `fremond impact` refuses law parameters out of range, unknown law types and unknown potentials
# (docs/problem-file.md): p ≤ 1, q ≤ 1, r < 0, k < 0, e outside [0, 1], mu < 0. A per-contact list names the
# entry at fault.
source "$(dirname "$0")/impact_common.bash" "$1"

# Frémond's normal power law: p > 1, k ≥ 0.
refuse_edit "p = 1" "law.normal.p" "must be > 1, got 1" \
  fremond_point.json 'd["law"]["normal"]["p"] = 1'
refuse_edit "p = 0.5" "law.normal.p" "must be > 1, got 0.5" \
  fremond_point.json 'd["law"]["normal"]["p"] = 0.5'
refuse_edit "p list entry <= 1" "law.normal.p[1]" "must be > 1, got 0.5" \
  fremond_per_contact.json 'd["law"]["normal"]["p"] = [2, 0.5]'
refuse_edit "normal k < 0" "law.normal.k" "must be >= 0, got -1" \
  fremond_point.json 'd["law"]["normal"]["k"] = -1'
refuse_edit "normal k list entry < 0" "law.normal.k[0]" "must be >= 0, got -6" \
  fremond_per_contact.json 'd["law"]["normal"]["k"] = [-6, 3]'

# The viscous dead zone: q > 1, r ≥ 0, k ≥ 0.
refuse_edit "q = 1" "law.tangential.q" "must be > 1, got 1" \
  fremond_viscous_point.json 'd["law"]["tangential"]["q"] = 1'
refuse_edit "q list entry < 1" "law.tangential.q[1]" "must be > 1, got 0" \
  fremond_per_contact.json 'd["law"]["tangential"]["q"] = [2, 0]'
refuse_edit "r < 0" "law.tangential.r" "must be >= 0, got -0.2" \
  fremond_viscous_point.json 'd["law"]["tangential"]["r"] = -0.2'
refuse_edit "r list entry < 0" "law.tangential.r[1]" "must be >= 0, got -0.1" \
  fremond_per_contact.json 'd["law"]["tangential"]["r"] = [0.2, -0.1]'
refuse_edit "tangential k < 0" "law.tangential.k" "must be >= 0, got -2" \
  fremond_viscous_point.json 'd["law"]["tangential"]["k"] = -2'

# Restitution e in [0, 1].
refuse_edit "e > 1 (newton)" "law.e" "must lie in [0, 1], got 1.5" \
  newton_bar.json 'd["law"]["e"] = 1.5'
refuse_edit "e < 0 (poisson)" "law.e" "must lie in [0, 1], got -0.5" \
  poisson_bar.json 'd["law"]["e"] = -0.5'
refuse_edit "e > 1 (newton_coulomb)" "law.e" "must lie in [0, 1]" \
  newton_coulomb_point.json 'd["law"]["e"] = 2'
refuse_edit "e list entry > 1 (poisson_coulomb)" "law.e[1]" "must lie in [0, 1], got 1.25" \
  poisson_coulomb_two_contacts.json 'd["law"]["e"] = [0.5, 1.25]'

# Friction mu ≥ 0.
refuse_edit "mu < 0 (newton_coulomb)" "law.mu" "must be >= 0, got -0.1" \
  newton_coulomb_point.json 'd["law"]["mu"] = -0.1'
refuse_edit "mu < 0 (poisson_coulomb)" "law.mu" "must be >= 0, got -1" \
  poisson_coulomb_point.json 'd["law"]["mu"] = -1'
refuse_edit "mu list entry < 0" "law.mu[0]" "must be >= 0, got -0.1" \
  poisson_coulomb_two_contacts.json 'd["law"]["mu"] = [-0.1, 0.2]'
refuse_edit "mu < 0 (fremond coulomb)" "law.tangential.mu" "must be >= 0, got -1" \
  fremond_coulomb_point.json 'd["law"]["tangential"]["mu"] = -1'

# Unknown names.
refuse_edit "unknown law type" "law.type" "unknown value 'elastic'" \
  newton_bar.json 'd["law"]["type"] = "elastic"'
refuse_edit "law type in capitals" "law.type" "unknown value 'Newton'" \
  newton_bar.json 'd["law"]["type"] = "Newton"'
refuse_edit "unknown normal potential" "law.normal.potential" "unknown potential 'quadratic'" \
  fremond_point.json 'd["law"]["normal"]["potential"] = "quadratic"'
refuse_edit "unknown tangential potential" "law.tangential.potential" \
  "unknown potential 'viscous'" \
  fremond_viscous_point.json 'd["law"]["tangential"]["potential"] = "viscous"'
refuse_edit "coulomb as a normal potential" "law.normal.potential" "tangential law only" \
  fremond_point.json 'd["law"]["normal"] = {"potential": "coulomb", "mu": 1}'

finish
