# `fremond impact` refuses matrices and lists of the wrong size or shape (docs/problem-file.md): M n×n, W_N and
# W_T n×c, w_N and w_T c entries, qdot_A n entries, per-contact parameters one value or c.
source "$(dirname "$0")/impact_common.bash" "$1"

# Mass matrix.
refuse_edit "M not square" "M" "must be square, got 1x2" fremond_point.json 'd["M"] = [[2, 0]]'
refuse_edit "M rows of different lengths" "M[1]" "every row needs the same length" \
  newton_coulomb_point.json 'd["M"] = [[1, 0], [0]]'
refuse_edit "M empty" "M" "empty" fremond_point.json 'd["M"] = []'
refuse_edit "M a number" "M" "must be a matrix (a list of rows), got the number 2" \
  fremond_point.json 'd["M"] = 2'
refuse_edit "M a flat list" "M[0]" "must be a list of numbers (a matrix row)" fremond_point.json 'd["M"] = [2]'

# Contact directions.
refuse_edit "W_N rows != n" "W_N" "must have 2 rows" newton_coulomb_point.json 'd["W_N"] = [[1]]'
refuse_edit "W_N a flat list" "W_N[0]" "must be a list of numbers (a matrix row)" newton_coulomb_point.json \
  'd["W_N"] = [0, 1]'
refuse_edit "W_T columns != W_N columns" "W_T" "must be 2x1 like W_N, got 2x2" \
  newton_coulomb_point.json 'd["W_T"] = [[1, 0], [0, 1]]'
refuse_edit "W_T rows != n" "W_T" "must be 2x1 like W_N, got 1x1" \
  newton_coulomb_point.json 'd["W_T"] = [[1]]'
refuse_edit "W_T given empty" "W_T" "must be 2x1 like W_N, got 0x0" \
  newton_coulomb_point.json 'd["W_T"] = []'

# Per-contact vectors.
refuse_edit "w_N length != c" "w_N" "must have 1 entries (one per contact), got 2" \
  newton_coulomb_point.json 'd["w_N"] = [0, 0]'
refuse_edit "w_N given empty" "w_N" "must have 1 entries (one per contact), got 0" \
  newton_coulomb_point.json 'd["w_N"] = []'
refuse_edit "w_T length != c" "w_T" "must have 1 entries (one per contact), got 3" \
  newton_coulomb_point.json 'd["w_T"] = [0, 0, 0]'
refuse_edit "w_T without W_T" "w_T" "given without W_T" \
  fremond_point.json 'd["w_T"] = [0]'
refuse_edit "w_N a number" "w_N" "must be a list of numbers" \
  newton_coulomb_point.json 'd["w_N"] = 0'
refuse_edit "qdot_A length != n" "qdot_A" "must have 2 entries, got 3" \
  newton_coulomb_point.json 'd["qdot_A"] = [2, -1, 0]'
refuse_edit "qdot_A a matrix" "qdot_A[0]" "must be a number, got a list" \
  fremond_point.json 'd["qdot_A"] = [[-3]]'

# Per-contact law parameters: one value, or one per contact (docs/problem-file.md).
refuse_edit "law.e list too long" "law.e" "needs one value or one per contact (1), got a list of 2" \
  newton_bar.json 'd["law"]["e"] = [0.9, 0.9]'
refuse_edit "law.e empty list" "law.e" "an empty list" newton_bar.json 'd["law"]["e"] = []'
refuse_edit "law.mu list too short" "law.mu" \
  "needs one value or one per contact (2), got a list of 3" \
  poisson_coulomb_two_contacts.json 'd["law"]["mu"] = [0.1, 0.2, 0.3]'
refuse_edit "law.normal.k list of wrong length" "law.normal.k" \
  "needs one value or one per contact (2), got a list of 3" \
  fremond_per_contact.json 'd["law"]["normal"]["k"] = [1, 2, 3]'
refuse_edit "law.tangential.r list of wrong length" "law.tangential.r" \
  "needs one value or one per contact (1), got a list of 2" \
  fremond_viscous_point.json 'd["law"]["tangential"]["r"] = [0.1, 0.2]'
refuse_edit "law.tangential.mu list of wrong length" "law.tangential.mu" \
  "needs one value or one per contact (1), got a list of 2" \
  fremond_coulomb_point.json 'd["law"]["tangential"]["mu"] = [0.1, 0.2]'
refuse_edit "law.e a list of lists" "law.e[0]" "must be a number, got a list" \
  poisson_coulomb_two_contacts.json 'd["law"]["e"] = [[0.5], [0.5]]'

finish
