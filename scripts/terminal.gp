# scripts/terminal.gp - the output terminal of every gapbeam figure script (loaded by each).
#
# Variables read (set them with gnuplot -e or scripts/plot.sh --format):
#   format   'png' (default), 'pdf' (vector, pdfcairo) or 'svg' (vector)
#   width, height   the picture's size in pixels (PNG, SVG); a PDF is width/100 x height/100
#                   inches with an 8-point font, which keeps the proportions of the PNG
# Sets: the terminal, UTF-8 encoding (labels use micro signs: µε), and `cairo` = 1 when the
# terminal draws with cairo (pngcairo, pdfcairo, svg) else 0 (libgd png: larger points needed).
if (!exists("format") || strlen(format) == 0) { format = "png" }
if (!exists("width")) { width = 900 }
if (!exists("height")) { height = 600 }
set encoding utf8
cairo = 1
if (format eq "pdf") {
   set terminal pdfcairo noenhanced size (width/100.0), (height/100.0) font ",8"
} else {
   if (format eq "svg") {
      set terminal svg noenhanced size width, height font ",11" background rgb "white"
   } else {
      if (format ne "png") {
         print sprintf("terminal.gp: format = '%s': expected 'png', 'pdf' or 'svg'", format)
         exit status 1
      }
      if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) {
         set terminal pngcairo noenhanced size width, height font ",11"
      } else {
         set terminal png noenhanced size width, height
         cairo = 0
      }
   }
}
