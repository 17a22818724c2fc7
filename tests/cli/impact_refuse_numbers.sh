# `fremond impact` refuses numbers that are not finite and values that are not numbers (docs/problem-file.md).
# Standard JSON has no NaN or infinity (their spellings are refused as bad JSON, see
# impact_refuse_input.sh); 1e999 is valid JSON that overflows a double, i.e. an infinity.
source "$(dirname "$0")/impact_common.bash" "$1"

# Infinite numbers, wherever a number is read.
refuse_edit "M entry 1e999" "M[0][0]" "must be a finite number, got 1e999" \
  fremond_point.json 'd["M"][0][0] = raw("1e999")'
refuse_edit "W_N entry -1e999" "W_N[1][0]" "must be a finite number, got -1e999" \
  newton_coulomb_point.json 'd["W_N"][1][0] = raw("-1e999")'
refuse_edit "W_T entry 1e999" "W_T[0][0]" "must be a finite number" \
  newton_coulomb_point.json 'd["W_T"][0][0] = raw("1e999")'
refuse_edit "w_N entry 1e999" "w_N[0]" "must be a finite number" \
  newton_coulomb_point.json 'd["w_N"][0] = raw("1e999")'
refuse_edit "w_T entry 1e999" "w_T[0]" "must be a finite number" \
  newton_coulomb_point.json 'd["w_T"][0] = raw("1e999")'
refuse_edit "qdot_A entry 1e999" "qdot_A[1]" "must be a finite number" \
  newton_coulomb_point.json 'd["qdot_A"][1] = raw("1e999")'
refuse_edit "law.e 1e999" "law.e" "must be a finite number" \
  newton_bar.json 'd["law"]["e"] = raw("1e999")'
refuse_edit "law.mu 1e999" "law.mu" "must be a finite number" \
  newton_coulomb_point.json 'd["law"]["mu"] = raw("1e999")'
refuse_edit "law.normal.k 1e999" "law.normal.k" "must be a finite number" \
  fremond_point.json 'd["law"]["normal"]["k"] = raw("1e999")'
refuse_edit "law.normal.p list entry 1e999" "law.normal.p[1]" "must be a finite number" \
  fremond_per_contact.json 'd["law"]["normal"]["p"] = [2, raw("1e999")]'
refuse_edit "law.tangential.r 1e999" "law.tangential.r" "must be a finite number" \
  fremond_viscous_point.json 'd["law"]["tangential"]["r"] = raw("1e999")'
refuse_edit "law.tangential.mu 1e999 (coulomb)" "law.tangential.mu" "must be a finite number" \
  fremond_coulomb_point.json 'd["law"]["tangential"]["mu"] = raw("1e999")'

# Finite numbers whose energy or contact velocity overflows: nothing can be certified there.
refuse_edit "qdot_A whose kinetic energy overflows" "qdot_A" "kinetic energy 1/2 qdot_A^T M qdot_A overflows" \
  newton_coulomb_point.json 'd["qdot_A"] = [0, -3e154]'
refuse_edit "W_N whose contact velocity overflows" "W_N" "contact 0: the normal velocity D_NA" \
  newton_coulomb_point.json 'd["W_N"][1][0] = 1e308; d["qdot_A"] = [0, -2]'

# Values that are not numbers: never read as 0, 1 or a default.
refuse_edit "M entry a string" "M[0][0]" 'must be a number, got a string "2"' \
  fremond_point.json 'd["M"][0][0] = "2"'
refuse_edit "W_N entry null" "W_N[0][0]" "must be a number, got null" \
  fremond_point.json 'd["W_N"][0][0] = None'
refuse_edit "qdot_A entry a boolean" "qdot_A[0]" "must be a number, got a boolean (true)" \
  fremond_point.json 'd["qdot_A"][0] = True'
refuse_edit "qdot_A entry an object" "qdot_A[0]" "must be a number, got an object" \
  fremond_point.json 'd["qdot_A"][0] = {"v": 1}'
refuse_edit "law.e a string" "law.e" "must be a number or a list of numbers" \
  newton_bar.json 'd["law"]["e"] = "0.9"'
refuse_edit "law.e null" "law.e" "must be a number or a list of numbers" \
  newton_bar.json 'd["law"]["e"] = None'
refuse_edit "law.mu a boolean" "law.mu" "must be a number or a list of numbers" \
  newton_coulomb_point.json 'd["law"]["mu"] = False'
refuse_edit "law.mu list entry null" "law.mu[1]" "must be a number, got null" \
  poisson_coulomb_two_contacts.json 'd["law"]["mu"] = [0.1, None]'
refuse_edit "law.normal.p a string" "law.normal.p" "must be a number or a list of numbers" \
  fremond_point.json 'd["law"]["normal"]["p"] = "2"'
refuse_edit "law.tangential.k null" "law.tangential.k" "must be a number or a list of numbers" \
  fremond_viscous_point.json 'd["law"]["tangential"]["k"] = None'

finish
