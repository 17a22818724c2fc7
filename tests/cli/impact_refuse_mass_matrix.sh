# `fremond impact` refuses a mass matrix that is not symmetric positive definite (docs/problem-file.md).
source "$(dirname "$0")/impact_common.bash" "$1"

refuse_edit "M not symmetric" "M" "must be symmetric; M[0][1] = 0.5 but M[1][0] = 0" \
  newton_coulomb_point.json 'd["M"] = [[1, 0.5], [0, 1]]'
refuse_edit "M indefinite" "M" "must be positive definite" \
  newton_coulomb_point.json 'd["M"] = [[1, 2], [2, 1]]'
refuse_edit "M singular" "M" "must be positive definite" \
  newton_coulomb_point.json 'd["M"] = [[1, 0], [0, 0]]'
refuse_edit "M negative" "M" "must be positive definite" fremond_point.json 'd["M"] = [[-2]]'
refuse_edit "M zero" "M" "must be positive definite" fremond_point.json 'd["M"] = [[0]]'
refuse_edit "M of the bar, not symmetric" "M" "must be symmetric" \
  newton_bar.json 'd["M"][2][0] = 0.1'

finish
