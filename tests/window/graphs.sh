# The graphs window, sourced by inner.sh (its ok/bad/shot/differ/find_window/
# wait_exit): G opens it over the swinging cradle, and after 12 s Shift+G
# writes the recorded series as CSV, with its header and 10 s of rows or more.
"$bin" --width 480 --height 240 > "$work/graphs.log" 2>&1 &
pid=$!
wid=$(find_window)
xdotool windowfocus "$wid" 2>/dev/null; sleep 1
shot nographs; xdotool key g; sleep 1; shot graphs
d=$(differ nographs graphs)
[ "$d" != "0" ] && ok "G opens the graphs ($d pixels)" || bad "G opens the graphs"
xdotool key space; sleep 12
xdotool key shift+g; sleep 1; shot graphs_csv
xdotool key Escape
wait_exit
csv=$(ls "$work"/newtons-cradle-*.csv 2>/dev/null | head -n 1)
span=$([ -n "$csv" ] && python3 -c '
import csv, sys
rows = list(csv.reader(open(sys.argv[1])))
assert rows[0][:6] == ["t_s", "energy_J", "energy_rel_error", "lost_contacts_J", "lost_drag_J", "momentum_kg_m_s"], rows[0]
ts = [float(r[0]) for r in rows[1:]]
print(f"{len(ts)} rows over {ts[-1] - ts[0]:.1f} s" if ts[-1] - ts[0] >= 10 else "short")
' "$csv" 2>&1)
grep -q "notice: saved graphs newtons-cradle-" "$work/graphs.log" && [ "${span#* rows over }" != "$span" ] \
  && ok "Shift+G saves the graphs as CSV ($span)" || bad "Shift+G saves the graphs as CSV ('$span')"
