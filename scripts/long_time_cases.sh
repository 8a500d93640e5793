# The long-time cases of the paper (scene|dt|t_end|schemes), sourced by
# scripts/build_paper.sh and scripts/sanitized_studies.sh so that both run the
# same ones: long_time_cases quick|full sets the array lt_cases.
long_time_cases() {
  if [ "$1" = quick ]; then
    lt_cases=("free_body_hlw|0.1|1e3|dmv rkmk4 split-exact quat/rk4" "heavy_top_trindade_1|2e-3|20|lgvi rkmk4 simo-wong")
  else
    lt_cases=("free_body_hlw|0.1|1e6|dmv dmv-pre4 lgvi@suzuki4 rkmk4 cf4 rkmk-gauss4 simo-wong split-exact quat/rk4 matrix/rk4"
              "heavy_top_trindade_1|1e-3|1e3|lgvi rkmk4 rkmk-gauss4 split-exact simo-wong quat/rk4")
  fi
}
