<?xml version="1.0" encoding="utf-8"?>
<!DOCTYPE TS>
<TS version="2.1">
<context>
    <name>@default</name>
    <message>
        <location filename="../birdseye_qgis/gui/plugin.py" line="109"/>
        <source>The BirdsEye Processing provider could not be registered.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/plugin.py" line="120"/>
        <source>&amp;BirdsEye</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/plugin.py" line="122"/>
        <source>BirdsEye</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/plugin.py" line="125"/>
        <source>BirdsEye algorithms…</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/plugin.py" line="127"/>
        <source>Open the Processing toolbox showing the BirdsEye algorithms</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/plugin.py" line="196"/>
        <source>The Processing plugin is not active: enable it under Plugins ▸ Manage and Install Plugins, then try again.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/plugin.py" line="247"/>
        <source>The &apos;{title}&apos; panel could not be opened ({module}.{cls}: {error}).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="73"/>
        <source>Review clusters</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="209"/>
        <source>Review setup</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="213"/>
        <source>choose one or more detection layers</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="214"/>
        <source>Outputs of Detect targets over one flight (several checkpoints or thresholds are reviewed together: one verdict per spot).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="270"/>
        <source>Detections</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="221"/>
        <source>Frames</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/field_package.py" line="361"/>
        <source>Geotags</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="233"/>
        <source>GeoPackage holding the append-only verdict log (table birdseye_verdicts). Default: the first detection layer&apos;s GeoPackage, else one next to the project.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="237"/>
        <source>Verdict log</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="239"/>
        <source>Recorded with every verdict.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="241"/>
        <source>Reviewer</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="243"/>
        <source>Clustering and matching</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="268"/>
        <source>DBSCAN minimum points per neighbourhood (itself included).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="287"/>
        <source>Size of the image window cut around a detection.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="294"/>
        <source>Map scale the canvas zooms to around each unit.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="295"/>
        <source>Grid cell</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="295"/>
        <source>EPS</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="295"/>
        <source>Min. points</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="295"/>
        <source>EPS_PRED</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="295"/>
        <source>Edge buffer</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="295"/>
        <source>Chip window</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="295"/>
        <source>Map scale</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="303"/>
        <source>Start / resume review</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="317"/>
        <source>No review started</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="328"/>
        <source>All layers</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="338"/>
        <source>Fired by</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="340"/>
        <source>Show</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="371"/>
        <source>Previous (P)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="373"/>
        <source>Next (N)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="390"/>
        <source>Undo (Ctrl+Z)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="408"/>
        <source>Propagate to units within {:.2f} m</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="409"/>
        <source>Off by default. When on, a verdict also votes (provenance propagated:{rule}) on the units chained to this one by gaps of at most {eps:.2f} m; conflicting votes are resolved under the three conventions, all shown.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="414"/>
        <source>Next unit after a verdict</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="421"/>
        <source>&lt;b&gt;Scores per detection layer&lt;/b&gt; — after review under each tie-break convention</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="423"/>
        <source>Recall and the geotag-matched cluster fraction (GMCF), computed as Evaluate detections computes them from this verdict log.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="427"/>
        <source>before
review</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="431"/>
        <source>After review, {}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="448"/>
        <source>GMCF is a lower bound on precision, not precision; recall after review is an upper bound (≥). The spread between the conventions is part of the result.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="236"/>
        <source>Choose at least one detection layer (an output of Detect targets).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="244"/>
        <source>Choose a GeoPackage for the verdict log (save the project first to get one next to it).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="310"/>
        <source>{n} units from {k} layer(s); verdict log {path}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="382"/>
        <source>A layer of the review was removed from the project; the review stopped. Every verdict is in the log; choose the layers again to resume.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/model.py" line="76"/>
        <source>Added target</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="419"/>
        <source>&lt;b&gt;{pos}&lt;/b&gt; of {vis} shown · {done} of {n} units reviewed · {added} added</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="472"/>
        <source>An added target can only be withdrawn (0 or Backspace) or undone.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="483"/>
        <source>Saved: {key} → {verdict}{more} ({time} UTC)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="483"/>
        <source>, {} propagated vote(s)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="498"/>
        <source>Nothing to undo.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="502"/>
        <source>Undone: action {action} on {key} (rows appended; nothing deleted).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="526"/>
        <source>The verdict was NOT saved: {error}. Check that {path} is writable and not locked, then try again.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="541"/>
        <source>Click the map where the missed target is (Esc or right click cancels).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="562"/>
        <source>Added target {key} (Ctrl+Z undoes it).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="562"/>
        <source>A target is already recorded there.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="583"/>
        <source>No units: the detection layers have no clusters at these settings.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="584"/>
        <source>Nothing to show</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="596"/>
        <source>Loading frames…</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="604"/>
        <source>&lt;b&gt;Added target&lt;/b&gt; {key}&lt;br&gt;{lat:.7f}°, {lon:.7f}° · recorded as a target the detector missed (the &lt;i&gt;a&lt;/i&gt; term). 0 withdraws it.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/model.py" line="155"/>
        <source>geotag {ids} within {eps:.2f} m</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/model.py" line="155"/>
        <source>no geotag within {eps:.2f} m</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/model.py" line="162"/>
        <source>none yet</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/model.py" line="163"/>
        <source>the conventions disagree</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="465"/>
        <source>The frames could not be read: {}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="468"/>
        <source>No frame of the frame layer shows this spot.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="475"/>
        <source>frame {f}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="481"/>
        <source>{shown} of {n} frames</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="667"/>
        <source>updating…</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="676"/>
        <source>Scores could not be computed: {}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/model.py" line="100"/>
        <source>recall</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/model.py" line="100"/>
        <source>GMCF</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="308"/>
        <source>Review verdicts</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="493"/>
        <source>Cannot start the review</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="493"/>
        <source>Inputs changed since verdicts were recorded</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="237"/>
        <source>Sensor-bound calculator</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="282"/>
        <source>Camera</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="291"/>
        <source>A platform sets the camera and the pose-noise budget together.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="293"/>
        <source>Platform</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="296"/>
        <source>Camera calibration (Kalibr or OpenCV YAML)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="297"/>
        <source>Load fx, fy, cx, cy and the image size from a Kalibr camchain or OpenCV YAML file.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="301"/>
        <source>Calibration</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="94"/>
        <source>Height</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="362"/>
        <source>Label tolerance and altitudes</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="377"/>
        <source>e.g. 10, 20</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="378"/>
        <source>Heights above the ground in metres, separated by commas.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="386"/>
        <source>Verdicts</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="395"/>
        <source>Altitude</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="413"/>
        <source>Details for</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="427"/>
        <source>Your σ</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="427"/>
        <source>Share of
error</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="429"/>
        <source>The largest budget with no axis starved (maximum Σ log σ²) that meets the exact bound.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="429"/>
        <source>Each axis&apos;s share of the error of your budget at the worst pixel: improve the largest first.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="489"/>
        <source>Evaluate every pixel</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="490"/>
        <source>Re-evaluate on the full-resolution grid (stride 1 px), as the Processing algorithm does by default.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="497"/>
        <source>Run in Processing…</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="498"/>
        <source>Open the Sensor bound algorithm with these values, to write the JSON results, the HTML report and the λ_max raster.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="531"/>
        <source>Altitudes</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="644"/>
        <source>every pixel</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/map_context.py" line="81"/>
        <source>Verdict layer {uri} could not be loaded</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="36"/>
        <source>Sealed rule verified (seal {value}…, sealed {sealed_at}); arm '{name}': its operating point replaces the dialog's values: {value2}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="64"/>
        <source>{path}: not a sensorbound result (expected inputs.tolerance_px): {exc}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="69"/>
        <source>{path}: the pose-noise budget is rejected at {items}; labels of σ = {value:g} px would not contain the projection error there</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="310"/>
        <source>{n_labels} labels in {n_frames_with_labels} of {n_frames} frames (labels per labelled frame: mean {mean:g}, max {max}); {n_geotags_in_view} of {n_geotags} geotags in view (frames per geotag: mean {mean2:g}, max {max2})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="329"/>
        <source>{n_occluded} projections were hidden behind terrain (not written)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="332"/>
        <source>{n_edge} projections fell within the edge buffer (not written)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="340"/>
        <source>{n_never} geotag(s) never in view of any frame: {shown}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="355"/>
        <source>{value} image(s) could not be read for tiles; first: {value2}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/dem.py" line="145"/>
        <source>DEM {source}: {value}×{value2} cells of {cell_size_m:g} m, heights {value3:.1f}…{value4:.1f} m ({vertical_datum})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="69"/>
        <source>{always}; for some inputs: {sometimes}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="71"/>
        <source>for some inputs: {sometimes}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="72"/>
        <source>no algorithm (developer tools only)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="79"/>
        <source>missing</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="81"/>
        <source>update from {version}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="83"/>
        <source>installed by BirdsEye ({version})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="87"/>
        <source>installed ({version})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="134"/>
        <source>BirdsEye — Python packages</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="153"/>
        <source>Package</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="153"/>
        <source>State</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="153"/>
        <source>Needed by</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="176"/>
        <source>Install</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="180"/>
        <source>Show pip&apos;s log</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="350"/>
        <source>Close</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="231"/>
        <source>Every Python package BirdsEye&apos;s algorithms need is installed in the Python QGIS runs.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="312"/>
        <source>Installing {names}…</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="318"/>
        <source>Cancel</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="335"/>
        <source>Installed: {names}. The algorithms can use them now; no restart needed.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="335"/>
        <source>nothing new</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="340"/>
        <source>The installation failed: {message}
pip&apos;s log is below; the packages already there are unchanged.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="346"/>
        <source>Cancelled; nothing was installed.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="358"/>
        <source>Cancelling…</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/plugin.py" line="53"/>
        <source>Review clusters: walk through the detected clusters beside the survey, judge each, and see recall and GMCF before and after review</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/plugin.py" line="56"/>
        <source>Sensor-bound calculator: which pose-noise budget keeps labels within their pixel tolerance for a camera and flying height</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/plugin.py" line="218"/>
        <source>Install dependencies…</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/plugin.py" line="147"/>
        <source>Install the Python packages BirdsEye&apos;s algorithms need</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/plugin.py" line="216"/>
        <source>Some algorithms need Python packages that are not installed: {names}.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="255"/>
        <source>How detections become review units. Consensus clusters (the default) pool the layers and judge each spot once. The method&apos;s: detections within EPS_PRED of an in-view geotag are set aside one by one; per frame, the rest are grouped so that every two detections of a group are at most {px:.0f} px apart; each group is a unit, so a spot is judged once per frame.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="295"/>
        <source>Review units</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="349"/>
        <source>How roll, pitch and yaw turn the camera. As the method: about the camera&apos;s x, y and optical axes; nadir, image top towards the nose: roll and pitch trade places.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="353"/>
        <source>Mount</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/dem.py" line="91"/>
        <source>{GROUND_MODEL}: the method&apos;s plane stands in for the level ground; with a terrain model ({DEM}) the terrain is the ground. Give one or the other.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="77"/>
        <source>no release for Python {version}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="85"/>
        <source>installed ({version}; untested outside {versions})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="153"/>
        <source>Versions</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="223"/>
        <source>BirdsEye&apos;s algorithms need {count} Python package(s) that the Python QGIS runs does not have. Tick the ones to install and press Install: pip installs them, at versions that suit this Python and the packages QGIS already has, with what they depend on, into a folder of your QGIS profile:
{folder}
QGIS&apos;s own packages are not changed. pip downloads them from the Python Package Index (or the index your pip is set up to use).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="320"/>
        <source>Of these, review targets: {n_in_view} of {n_targets} in view, {n_labels} labels.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="325"/>
        <source>Hard negatives: {n_in_view} of {n_clusters} in view, in {n_frames} frame(s); {n_tiles} hard-negative tile(s) written.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="267"/>
        <source>Optional — {title} for Train detector ({build} build{why}): {state}. It is installed into its own folder, {folder}, and runs in a separate training process: QGIS itself never loads it. Several hundred MB (the CUDA build: gigabytes).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="267"/>
        <source>, an NVIDIA driver is present</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="276"/>
        <source>Install {title}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="283"/>
        <source>The detections were placed on {ground}, which cannot be used here ({reason}). Chips and geotags in view stand on the level plane instead: positions in the chips and the scores may differ from those of Evaluate detections given that DEM.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="288"/>
        <source>The review stands on the level plane, not on the detections&apos; DEM</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/layers.py" line="499"/>
        <source>the camera model of frame {frame} was cut at {length} characters: {format} keeps at most {length} characters in a text field and a camera model needs about 500: the layer was probably saved to it after the import (Save Features As…). Save the original frame layer as a GeoPackage (.gpkg) instead, or run the import again with its output written to a GeoPackage (or to this format: the import then splits the camera over fields camera, camera_2, …).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/layers.py" line="499"/>
        <source>the layer&apos;s file format (e.g. ESRI Shapefile)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/layers.py" line="546"/>
        <source>The output&apos;s format keeps at most {n} characters in a text field: each frame&apos;s camera model goes on in fields {fields}; keep them with the layer.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="306"/>
        <source>Training: {stage}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="308"/>
        <source>Training process {pid} started: torch {torch} on {device} ({threads} threads), backbone {backbone}.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="313"/>
        <source>{stage} step {step}: loss {loss:.4f}, validation {val} ({seconds:.0f} s)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="317"/>
        <source>Checkpoint written: {path} ({stage}, step {step})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/dem.py" line="135"/>
        <source>{layer}: its detections were placed on {recorded}; {DEM} is {given}. Check that both hold the same terrain in the same vertical reference.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/dem.py" line="119"/>
        <source>DEM against the frames: {check}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="225"/>
        <source>The survey points (Import geotags). Point layers that BirdsEye made for something else (detections, clusters, waypoints, verdicts) are not listed.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="236"/>
        <source>the detections&apos; GeoPackage</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="247"/>
        <source>One per spot</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="248"/>
        <source>One per spot and frame (the method&apos;s)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="249"/>
        <source>Consensus clusters: one unit per spot, pooling all layers</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="251"/>
        <source>The method&apos;s units: per frame, complete linkage at {px:.0f} px</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="392"/>
        <source>Missed target (A)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="255"/>
        <source>Install the ticked packages into {folder}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="257"/>
        <source>Tick a package in the list to install it.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="259"/>
        <source>Nothing to install: every package in the list is installed or has no release for this Python.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="277"/>
        <source>Install {names} into {folder}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="280"/>
        <source>{title} is installed</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="281"/>
        <source>Nothing to install: {state}.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/dependencies.py" line="316"/>
        <source>pip is installing; press Cancel to stop it.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="362"/>
        <source>Choose the layers above and press Start: each unit to judge shows here.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="400"/>
        <source>The frames that show the unit</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="72"/>
        <source>DJI RTK drone, poses from photos</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="79"/>
        <source>Horizontal position error across the flight direction (image right), metres.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="80"/>
        <source>Horizontal position error along the flight direction (image down), metres.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="81"/>
        <source>Vertical position / altimeter error (along the optical axis), metres.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="82"/>
        <source>Roll attitude error, degrees; the camera mount says which way it turns the camera.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="84"/>
        <source>Pitch attitude error, degrees; the camera mount says which way it turns the camera.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="86"/>
        <source>Heading error (about the vertical / optical axis), degrees.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="90"/>
        <source>Across (x)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="90"/>
        <source>Along (y)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="91"/>
        <source>Height (z)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="94"/>
        <source>Roll</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="95"/>
        <source>Pitch</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="95"/>
        <source>Yaw</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="93"/>
        <source>Across</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="93"/>
        <source>Along</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="97"/>
        <source>As the method</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="98"/>
        <source>Nadir, image top forward</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="100"/>
        <source>The spread of a label is the variance of where pose noise moves it, in square pixels (px²): its standard deviation squared.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="102"/>
        <source>Total spread, sup tr Σ: the largest sum of the spreads along u and v over the image (px²), the trace of the label covariance Σ. Quick to check and pessimistic: it is never smaller than the largest spread.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="105"/>
        <source>Largest spread, sup λmax: the largest spread in the worst direction over the image (px²), the largest eigenvalue λmax of the label covariance Σ. This is what the tolerance limits.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="108"/>
        <source>Trace bound: safety factor κ* = λ_target / total spread. Sufficient but pessimistic: when it accepts, the exact bound accepts too.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="110"/>
        <source>Exact bound: safety factor κ* = λ_target / largest spread, the exact eigenvalue bound. Accept (✓) when κ* ≥ 1: every variance of the pose noise may grow by κ* (every σ by √κ*) and labels still stay within their tolerance.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="179"/>
        <source>✓ labels stay within their tolerance</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="179"/>
        <source>✗ labels leave their tolerance</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="181"/>
        <source>&lt;b&gt;{altitude} m&lt;/b&gt;: &lt;span style='color:{colour}'&gt;&lt;b&gt;{verdict}&lt;/b&gt;&lt;/span&gt; (safety factor κ* {kappa})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="188"/>
        <source>left</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="188"/>
        <source>right</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="189"/>
        <source>top</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="189"/>
        <source>bottom</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="191"/>
        <source>the {v}-{u} corner</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="193"/>
        <source>the {side} edge</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="194"/>
        <source>inside the frame</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="218"/>
        <source>Accepted: κ* = {k}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="218"/>
        <source>Rejected: κ* = {k}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="299"/>
        <source>a Kalibr or OpenCV YAML file</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="311"/>
        <source>Focal length fx: along u (image right), in pixels</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="311"/>
        <source>Focal length fy: along v (image down), in pixels</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="311"/>
        <source>Principal point cx: where the optical axis meets the image, u (px)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="311"/>
        <source>Principal point cy: where the optical axis meets the image, v (px)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="311"/>
        <source>Image width W (px)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="311"/>
        <source>Image height H (px)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="318"/>
        <source>Focal length</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="318"/>
        <source>fx, fy (px)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="318"/>
        <source>Principal point</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="318"/>
        <source>cx, cy (px)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="318"/>
        <source>Image size</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="318"/>
        <source>width × height (px)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="328"/>
        <source>Pose noise, one standard deviation (1σ)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="365"/>
        <source>Label tolerance: the radius r, in pixels, within which a label must stay around its target, at 3σ (99.7 % of the time).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="368"/>
        <source>Label radius r (3σ)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="373"/>
        <source>σ_label = r/3: the Gaussian sigma of the soft labels Write labels draws; its square λ_target = σ_label² is the spread a label may have.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="380"/>
        <source>Altitudes (m)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="395"/>
        <source>Total
spread</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="395"/>
        <source>Largest
spread</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="395"/>
        <source>Trace
bound</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="395"/>
        <source>Exact
bound</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="397"/>
        <source>Height above the ground.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="404"/>
        <source>Spread: how far pose noise scatters a label, in px² (a variance). Bounds: the safety factor κ* by which the pose noise may grow, ✓ when κ* ≥ 1; the exact bound decides, the trace bound is a quicker, pessimistic check.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="416"/>
        <source>The altitude whose budget table and spread map are shown.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="423"/>
        <source>The pixel (u, v) where the largest spread occurs; pixel (0, 0) is the centre of the top-left pixel.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="427"/>
        <source>Balanced
trace</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="427"/>
        <source>Balanced
exact</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="429"/>
        <source>The pose noise you entered (1σ).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="429"/>
        <source>The largest budget with no axis starved (maximum Σ log σ²) that meets the trace bound: each axis takes a sixth of it.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="470"/>
        <source>Spread over the image</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="473"/>
        <source>The largest spread λmax (px²) at each pixel; red: the tolerance λ_target, ○ the worst pixel, + the principal point.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="493"/>
        <source>Write labels with this σ…</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="494"/>
        <source>Open Write labels with its label sigma (SIGMA_PX) set to σ_label = r/3 px from this tolerance; you see the value before you run it.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="617"/>
        <source>Label sigma σ_label = r/3 = {value:.2f} px</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="644"/>
        <source>a preview: every {s} px and the frame edges</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="649"/>
        <source>A label may spread λ_target = (r/3)² = {lam:.4g} px². Evaluated at {grid}.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="657"/>
        <source>Cannot evaluate:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="670"/>
        <source>sup tr Σ = {value:.6g} px² at pixel ({u:.0f}, {v:.0f})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="673"/>
        <source>sup λmax = {value:.6g} px² at pixel ({u:.0f}, {v:.0f})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/sensor_bound_dock.py" line="693"/>
        <source>Worst pixel ({u:.0f}, {v:.0f}): {where}.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="271"/>
        <source>Cells (the method&apos;s)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="273"/>
        <source>What the minimum points count, as in Cluster detections: the detections in the grid cells within EPS (the default), or the occupied cells, one point each (the method&apos;s: a spot whose detections all fall in one cell never forms a unit).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="295"/>
        <source>Points count</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="41"/>
        <source>The rule was sealed before BirdsEye recorded what the minimum points count; its arms were chosen counting cells, so it is scored counting cells, as sealed.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="335"/>
        <source>{n} projections lay just beyond the image border, their label disc reaching in (not written)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="345"/>
        <source>{n} near a target in view but not labelled (edge buffer, beyond the border, an unresolved cluster)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="345"/>
        <source>{n} without a positive not wholly inside the surveyed area</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="345"/>
        <source>every tile of {n} frame(s) without a ground height</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="350"/>
        <source>Tiles: {positive} positive, {negative} negative written; skipped: {reasons}.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="350"/>
        <source>none</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="364"/>
        <source>Relief check ({source}): {n} label(s), largest displacement h·r/d {cm:.1f} cm = {px:.1f} px against the label radius {radius:.1f} px; {over} frame(s) exceed it</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="371"/>
        <source>frame {frame_id}: geotag {geotag_id}, {displacement_cm:g} cm = {displacement_px:g} px &gt; {label_radius_cm:g} cm = {label_radius_px:g} px</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="374"/>
        <source> (summary.json lists them all): {shown}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/dock.py" line="596"/>
        <source>Loading the raster…</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/model.py" line="164"/>
        <source>on the raster</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="201"/>
        <source>Not needed: the detections chosen were found on a raster (Detect targets on a raster). Their chips are cut from that raster, and the geotags in view are those it covers.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="203"/>
        <source>The flight&apos;s frame layer (Import flight log, Import drone images or Import camera solution): poses, camera and image of every frame. Only frame layers are listed. Detections found on a raster need none.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="465"/>
        <source>The raster could not be read: {}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="468"/>
        <source>This spot is off the raster.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="475"/>
        <source>raster</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/gui/review/widgets.py" line="481"/>
        <source>cut from the raster</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/field_package.py" line="104"/>
        <source>Needs RTK fixed</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/field_package.py" line="105"/>
        <source>Needs RTK fixed and ≤ {cm:g} cm horizontal accuracy</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/field_package.py" line="105"/>
        <source>Needs ≤ {cm:g} cm horizontal accuracy</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/field_package.py" line="362"/>
        <source>Points to visit</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/field_package.py" line="531"/>
        <source>Surveyed before</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/field_package.py" line="366"/>
        <source>Survey area</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/field_package.py" line="369"/>
        <source>Frame footprints</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/field_package.py" line="371"/>
        <source>Orthomosaic</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/field_package.py" line="388"/>
        <source>BirdsEye field survey: {name}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/field_package.py" line="397"/>
        <source>Use the best fix you can get</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/field_package.py" line="399"/>
        <source>3. QField settings › Positioning: “Use orthometric altitude from device” ON (heights go to {field}).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/field_package.py" line="402"/>
        <source>3. QField settings › Positioning: “Use orthometric altitude from device” OFF and no vertical grid shift (heights go to {field}).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/field_package.py" line="404"/>
        <source>1. Connect the RTK receiver; add each geotag with the crosshair snapped to your position (the GNSS button), never by tapping the map.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/field_package.py" line="404"/>
        <source>2. {fix}: wait for it before saving; hold the pole on the target&apos;s centre (label radius {r:g} m).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/field_package.py" line="492"/>
        <source>Label radius (m)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/field_package.py" line="494"/>
        <source>Geotag</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/field_package.py" line="502"/>
        <source>Fails: {what}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/field_package.py" line="504"/>
        <source>Meets the accuracy requirement</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/field_package.py" line="520"/>
        <source>Not visited</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/field_package.py" line="476"/>
        <source>Worker</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/field_package.py" line="477"/>
        <source>Note</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/field_package.py" line="485"/>
        <source>Class</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/field_package.py" line="487"/>
        <source>Height above MSL (m, receiver)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/field_package.py" line="487"/>
        <source>Ellipsoidal height (m, receiver)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/field_package.py" line="513"/>
        <source>Visit</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/field_package.py" line="513"/>
        <source>Why it is visited</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/field_package.py" line="513"/>
        <source>Question</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../birdseye_qgis/qgis_io/field_package.py" line="513"/>
        <source>Decision</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>BirdsEyeAlgorithm</name>
    <message>
        <location filename="../processing/algorithms/base.py" line="230"/>
        <source>Cancelled by the user.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/base.py" line="36"/>
        <source>1 · Field data</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/base.py" line="37"/>
        <source>2 · Flight planning</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/base.py" line="38"/>
        <source>3 · Training labels</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/base.py" line="39"/>
        <source>4 · Detection and review</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/base.py" line="40"/>
        <source>5 · Platform design</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/base.py" line="41"/>
        <source>6 · Simulation</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/base.py" line="269"/>
        <source>This algorithm needs the Python package(s) {names}, which the Python QGIS runs does not have. In QGIS, choose BirdsEye › Install dependencies… to install them; or install them yourself: python -m pip install {pins}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/base.py" line="276"/>
        <source>This algorithm needs the Python package(s) {names}, which have no release for the Python QGIS runs (Python {version}); it runs in a QGIS with a newer Python.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/base.py" line="163"/>
        <source>{name} must be between {lo:g} and {hi:g}{unit}, got {value:g}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/base.py" line="166"/>
        <source>{name} must be at least {lo:g}{unit}, got {value:g}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/base.py" line="169"/>
        <source>{name} must be at most {hi:g}{unit}, got {value:g}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/base.py" line="185"/>
        <source>{name}: {path} is a file; give a folder (a new one is made where none is).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/base.py" line="192"/>
        <source>{name}: {path} is a folder; give a file name.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/base.py" line="199"/>
        <source>{name}: {path} cannot be written ({folder} is read-only for you); choose another place.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/base.py" line="258"/>
        <source>{paths}: {reason}. Check that the path is right, that its folder can be written, and that no file has the name a folder needs (or the other way round).</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>ClusterDetections</name>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="53"/>
        <source>Detections (from Detect targets)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="65"/>
        <source>Clusters</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="67"/>
        <source>De-duplicated points</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="77"/>
        <source>DETECTIONS: the detection layer cannot be read.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="89"/>
        <source>The detection layer holds no detection with a position.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="164"/>
        <source>OUTPUT: the cluster layer cannot be created.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="187"/>
        <source>OUTPUT_POINTS: the point layer cannot be created.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="80"/>
        <source>{dropped} detection(s) without a position or score were left out</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="128"/>
        <source>No FRAMES given: every geotag is treated as in view.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="135"/>
        <source>{n_hit_clusters} of {n} clusters match an in-view geotag; {n_recovered} of {n_in_view} in-view geotags recovered.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="44"/>
        <source>Cluster detections</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="123"/>
        <source>{n} frame(s) without a ground height (flag no_ground_height; first: {items}) were not counted as processed: the geotags only they see are not in view.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="57"/>
        <source>Geotags (to mark the clusters hitting one)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="60"/>
        <source>Frames (only geotags in view match)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="147"/>
        <source>{n_det} detections → {n_points} de-duplicated points → {n} clusters ({NOISE_POINTS} points are noise; minimum points counted {counted}).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/clusterdetections.py" line="96"/>
        <source>The detections were found on a raster, which shows each target once: each detection can be a cluster by itself (MIN_SAMPLES {used}, not {asked}), and the geotags in view are those on the raster&apos;s valid pixels.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>ClusteringParametersMixin</name>
    <message>
        <location filename="../processing/parameters/clustering.py" line="40"/>
        <source>De-duplication grid cell (cm)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/clustering.py" line="43"/>
        <source>DBSCAN radius EPS (m)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/clustering.py" line="60"/>
        <source>Edge buffer of the in-view test (px)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/clustering.py" line="100"/>
        <source>{name}: give at least one detection layer.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/clustering.py" line="106"/>
        <source>{layer}: {n} detection(s) without a position or score left out</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/clustering.py" line="46"/>
        <source>DBSCAN minimum points (itself included)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/clustering.py" line="56"/>
        <source>Geotag match radius EPS_PRED (m)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/clustering.py" line="67"/>
        <source>Minimum points count</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/clustering.py" line="116"/>
        <source>{name}: give one frame layer per detection layer found on frames, in the same order (got {detections} detection layer(s), {on_frames} of them found on frames, and {frames} frame layer(s)); a layer found on a raster needs none.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>CompareDetectors</name>
    <message>
        <location filename="../processing/algorithms/comparedetectors.py" line="37"/>
        <source>Compare detectors</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/comparedetectors.py" line="51"/>
        <source>Detections of the old detector (before)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/comparedetectors.py" line="60"/>
        <source>Geotags</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/comparedetectors.py" line="67"/>
        <source>What changed</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/comparedetectors.py" line="69"/>
        <source>Comparison (JSON)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/comparedetectors.py" line="71"/>
        <source>Report (HTML)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/comparedetectors.py" line="85"/>
        <source>{name}: the layer cannot be read.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/comparedetectors.py" line="90"/>
        <source>{name}: {n} detection(s) without a position or score left out</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/comparedetectors.py" line="96"/>
        <source>Both layers come from the same model file (model_digest) at the same threshold: the comparison shows no change of detector.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/comparedetectors.py" line="110"/>
        <source>GEOTAGS: the layer holds no point with a position.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/comparedetectors.py" line="149"/>
        <source>OUTPUT: the change layer cannot be created.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/comparedetectors.py" line="177"/>
        <source>{name}: cannot write {path} ({exc})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/comparedetectors.py" line="54"/>
        <source>Detections of the new detector (same flight)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/comparedetectors.py" line="57"/>
        <source>Frames of the flight</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/comparedetectors.py" line="64"/>
        <source>Review verdicts (for scores after review)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/comparedetectors.py" line="115"/>
        <source>{name} was found on the raster {raster}: both layers are scored over the geotags in view of the frames and on the raster&apos;s pixels ({n} of {total} lie on the raster); its detections beyond the frames&apos; view are left out, and each of its detections can be a cluster by itself (one image shows a target once).</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>DemParametersMixin</name>
    <message>
        <location filename="../processing/parameters/dem.py" line="64"/>
        <source>DEM heights are measured from</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/dem.py" line="71"/>
        <source>Ground model without a DEM</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/dem.py" line="67"/>
        <source>Geoid undulation N (m; empty: EGM96)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/dem.py" line="61"/>
        <source>Terrain model (DEM; empty: level ground)</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>DesignParametersMixin</name>
    <message>
        <location filename="../processing/parameters/design.py" line="113"/>
        <source>Camera from {file}: {w}×{h} px, fx {fx:.4f}, fy {fy:.4f}, cx {cx:.4f}, cy {cy:.4f} px (the typed intrinsics are ignored).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/design.py" line="131"/>
        <source>{name}: the focal length must be greater than 0 px, got {value:g}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/design.py" line="161"/>
        <source>{name}: the label tolerance must be greater than 0 px, got {value:g}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/design.py" line="168"/>
        <source>Cancelled by the user.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/design.py" line="54"/>
        <source>Custom</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/design.py" line="99"/>
        <source>Platform {name}. Sources: {sources}.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/design.py" line="110"/>
        <source>{CALIBRATION}: {exc}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/design.py" line="122"/>
        <source>Camera of the platform: {w}×{h} px, fx {fx:.4f}, fy {fy:.4f}, cx {cx:.4f}, cy {cy:.4f} px (the typed intrinsics are ignored).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/design.py" line="102"/>
        <source>Pose sigmas of the platform: {sigmas} ({hint}; the typed SIGMAS are ignored), camera mount: {mount} (the chosen {MOUNT} is ignored).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/design.py" line="54"/>
        <source>Platform preset (Custom: the values below)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/design.py" line="73"/>
        <source>Pose sigmas 1σ: x, y, z (m), roll, pitch, yaw (°)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/design.py" line="76"/>
        <source>Camera mount</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/design.py" line="81"/>
        <source>Altitudes above the ground (m, comma-separated)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/design.py" line="86"/>
        <source>Label tolerance r (px, label radius at 3σ)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/design.py" line="57"/>
        <source>Camera calibration (YAML)</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>Detect</name>
    <message>
        <location filename="../processing/algorithms/detect.py" line="48"/>
        <source>Detections</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detect.py" line="50"/>
        <source>Heatmap folder (one PNG per frame)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detect.py" line="56"/>
        <source>SHA-256 of the model</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detect.py" line="75"/>
        <source>Model {name} (sha256 {value}…): {resolution_cm:g} cm/px, tiles {tile_size} px with {overlap_px} px overlap, threshold {used:g}{value2}.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detect.py" line="98"/>
        <source>{detections} detections in {processed} frames ({value:.2f} per frame); {edge} dropped within {edge_buffer_px:g} px of the border, {no_ground} whose ray missed the ground; {skipped} frames skipped.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detect.py" line="129"/>
        <source>Frame {frame_id}: {skipped}; skipped.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detect.py" line="148"/>
        <source>{n_coarse} frame(s) (e.g. {items}) are coarser than 1.5× the model's resolution of {resolution_cm:g} cm/px: targets look smaller than in training, so expect fewer detections (fly lower or use a model trained at that resolution).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detect.py" line="32"/>
        <source>Detect targets (ONNX heatmap model)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detect.py" line="89"/>
        <source>{FRAMES} has no CRS: the detections are written in {crs}, the UTM zone of the site.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detect.py" line="41"/>
        <source>Frames</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detect.py" line="44"/>
        <source>Edge buffer at the image border (px)</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>DetectRaster</name>
    <message>
        <location filename="../processing/algorithms/detectraster.py" line="39"/>
        <source>Detect targets on a raster (orthomosaic)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detectraster.py" line="46"/>
        <source>Raster (orthomosaic)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detectraster.py" line="48"/>
        <source>Only inside these polygons</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detectraster.py" line="51"/>
        <source>Only inside this extent</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detectraster.py" line="54"/>
        <source>Detections</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detectraster.py" line="59"/>
        <source>SHA-256 of the model</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detectraster.py" line="73"/>
        <source>Raster {width} × {height} px at {gsd:.2f} cm/px, bands {bands} as red, green, blue; model {name} (sha256 {digest}…) at {resolution:g} cm/px, threshold {used:g}.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detectraster.py" line="80"/>
        <source>The raster ({gsd:.2f} cm/px) is coarser than 1.5× the model's resolution of {resolution:g} cm/px: targets look smaller than in training, so expect fewer detections.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/detectraster.py" line="103"/>
        <source>{count} detections from {windows} windows ({skipped} outside the area asked for not read); {merged} found on a seam by two windows kept once.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>EvaluateDetections</name>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="61"/>
        <source>Detection layers (one per flight)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="63"/>
        <source>Geotags</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="65"/>
        <source>Frame layers (one per flight, same order)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="77"/>
        <source>Scores (JSON)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="79"/>
        <source>Report (HTML)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="93"/>
        <source>GEOTAGS: the geotag layer cannot be read.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="96"/>
        <source>GEOTAGS: the layer holds no point with a position.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="119"/>
        <source>{name}: {n_frames_without_ground} frame(s) without a ground height were not counted as processed</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="126"/>
        <source>OUTPUT_JSON: cannot write {out_json} ({exc})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="134"/>
        <source>OUTPUT_REPORT: cannot write {out_report} ({exc})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="49"/>
        <source>Evaluate detections (recall, GMCF)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="103"/>
        <source>ARM: names an arm of a sealed selection rule; give the rule (PREREGISTRATION) too, or leave ARM empty.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="69"/>
        <source>Review verdicts (for scores after review)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="72"/>
        <source>Sealed selection rule (JSON)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/evaluatedetections.py" line="75"/>
        <source>Arm to score (its name in the rule)</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>ImportCameras</name>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="38"/>
        <source>Align to the images&apos; GPS tags (needs IMAGES)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="76"/>
        <source>A COLMAP model&apos;s frame</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="87"/>
        <source>Solved frames</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="95"/>
        <source>Frames written</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="96"/>
        <source>Cameras the solution did not align</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="120"/>
        <source>Camera: {width}×{height} px, fx {fx:.2f}, fy {fy:.2f}, cx {cx:.2f}, cy {cy:.2f} ({source})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="124"/>
        <source>Output CRS: {value}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="47"/>
        <source>Import camera solution (Metashape, OpenDroneMap, COLMAP, Pix4D)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="98"/>
        <source>Median distance of the control points&apos; labels from their marks (px)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="100"/>
        <source>90th percentile of that distance (px)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="137"/>
        <source>SOLUTION_CRS: {crs} is not a projected CRS in metres; give the Pix4D project&apos;s output CRS (easting, northing and height in metres)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="152"/>
        <source>Control points</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="168"/>
        <source>Label check (pinned marks)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="38"/>
        <source>Georegistered in ECEF (COLMAP&apos;s model_aligner)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="38"/>
        <source>East-north-up at ENU_ORIGIN</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="66"/>
        <source>Camera solutions</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="66"/>
        <source>All files</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="71"/>
        <source>Image folder (matched by file name)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="82"/>
        <source>Output CRS of a Pix4D project</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="89"/>
        <source>Control points (as geotags)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="92"/>
        <source>Label check (pinned image marks)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="66"/>
        <source>Metashape .psx/.psz or other camera solution</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="73"/>
        <source>Ground height without tie points (m)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="79"/>
        <source>COLMAP ENU origin: lat, lon, height (m)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importcameras.py" line="84"/>
        <source>Output CRS (empty: the site&apos;s UTM zone)</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>ImportDjiImages</name>
    <message>
        <location filename="../processing/algorithms/importdjiimages.py" line="48"/>
        <source>Frames written</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importdjiimages.py" line="49"/>
        <source>Images that cannot be placed</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importdjiimages.py" line="65"/>
        <source>Not placed: {error}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importdjiimages.py" line="68"/>
        <source>Camera: {width}×{height} px, fx {fx:.1f}, fy {fy:.1f} ({source})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importdjiimages.py" line="72"/>
        <source>Output CRS: {value}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importdjiimages.py" line="24"/>
        <source>Import drone images</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importdjiimages.py" line="35"/>
        <source>Folder of drone images (JPEG)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importdjiimages.py" line="46"/>
        <source>Drone frames</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importdjiimages.py" line="37"/>
        <source>Camera calibration (YAML)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importdjiimages.py" line="40"/>
        <source>Output CRS (empty: the site&apos;s UTM zone)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importdjiimages.py" line="42"/>
        <source>Flight height above take-off (m)</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>ImportFlightLog</name>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="40"/>
        <source>Pose log (BirdsEye CSV or flight_data.db)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="46"/>
        <source>Camera calibration (Kalibr camchain or OpenCV YAML)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="49"/>
        <source>Camera frame rate (frames/s)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="52"/>
        <source>Minimum altimeter SNR (dB)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="54"/>
        <source>RTK filter</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="61"/>
        <source>Frames</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="63"/>
        <source>Flight line</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="78"/>
        <source>Camera: {width}×{height} px, fx {fx:.1f}, fy {fy:.1f} ({source})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="95"/>
        <source>Output CRS: {value}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="24"/>
        <source>Import flight log</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="56"/>
        <source>UTM zone of flight_data.db x, y</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="43"/>
        <source>Image folder</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importflightlog.py" line="58"/>
        <source>Output CRS (empty: the site&apos;s UTM zone)</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>ImportGeotags</name>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="73"/>
        <source>…or a point layer</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="75"/>
        <source>File format</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="85"/>
        <source>Fix filter</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="90"/>
        <source>Antenna pole height (m), subtracted from heights</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="93"/>
        <source>Output CRS (empty: UTM zone of the site)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="98"/>
        <source>Geotags</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="112"/>
        <source>Give either a geotag file (INPUT) or a point layer (INPUT_LAYER), not both and not neither.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="147"/>
        <source>The input holds no usable geotag.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="180"/>
        <source>No geotag is left to write (all were filtered out).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="150"/>
        <source>{n_problems} bad row(s) left out; first: {examples}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="165"/>
        <source>{dropped_not_fixed} geotag(s) without an RTK fixed solution were left out (fix filter: RTK fixed only)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="177"/>
        <source>{duplicates} geotag(s) lie within 2 cm of an earlier one (flag duplicate_2cm)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="182"/>
        <source>Output CRS: {value}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="39"/>
        <source>Import geotags</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="57"/>
        <source>Metres</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="57"/>
        <source>International feet (0.3048 m)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="57"/>
        <source>US survey feet (1200/3937 m)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="79"/>
        <source>Unit of heights and accuracies</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="142"/>
        <source>Reading: {note}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="157"/>
        <source>Fix quality of the input: {counts}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="161"/>
        <source>Horizontal accuracy of the input: median {median:.3f} m, worst {worst:.3f} m ({n_known} of {n_tags} geotags give one)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="169"/>
        <source>{dropped} geotag(s) with a horizontal accuracy worse than {limit:g} m were left out (MAX_H_ACCURACY_M)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="173"/>
        <source>{unknown} geotag(s) have no horizontal accuracy in the input and were kept (MAX_H_ACCURACY_M cannot judge them)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="57"/>
        <source>From the file (else metres)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="82"/>
        <source>Geoid undulation N (m; empty: EGM96)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="87"/>
        <source>Largest horizontal accuracy kept (m)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="70"/>
        <source>Geotag file (CSV, NMEA or field GeoPackage)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="95"/>
        <source>Append field decisions to review (.gpkg)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="125"/>
        <source>Reading: read as a BirdsEye field survey GeoPackage (QField): {path}, table &apos;{table}&apos;</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="138"/>
        <source>REVIEW_LOG is not used: only a field survey package (its GeoPackage) has decisions to append to a review.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="145"/>
        <source> Its {n} field decision(s) were appended to the review all the same.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="212"/>
        <source>Field survey: {n_tags} geotag(s), {n_fixed} RTK fixed, {n_accuracy} with a horizontal accuracy, {n_time} with a capture time; recorded by {workers}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="212"/>
        <source>no named worker</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="226"/>
        <source>Point to visit left out: {problem}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="231"/>
        <source>The review the package came from, {log}, is not there (moved?): give it as REVIEW_LOG to append the field decisions to it.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="236"/>
        <source>{n} review unit(s) have a field decision, but the package names no review and REVIEW_LOG is empty: the decisions are not written.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="240"/>
        <source>{n} decided point(s) to visit are not review units (no unit keys), so their decisions are not written to a review: {visits}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="244"/>
        <source>{n} point(s) to visit have no decision (not visited)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="247"/>
        <source>Field decisions: {note}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="249"/>
        <source>{n} review unit(s) already hold the field&apos;s decision from the same worker (imported before): not appended again</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/importgeotags.py" line="252"/>
        <source>Field decisions: {n} verdict(s) appended to the review {log} as {reviewers}</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>ModelParametersMixin</name>
    <message>
        <location filename="../processing/parameters/model.py" line="18"/>
        <source>ONNX model (empty: the bundled one)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/model.py" line="21"/>
        <source>Threshold (empty: the model&apos;s own)</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>MonteCarloBoundAlgorithm</name>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="61"/>
        <source>Monte Carlo samples</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="63"/>
        <source>Random seed</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="64"/>
        <source>Scaling study: smallest variance factor</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="66"/>
        <source>Scaling study: largest variance factor</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="68"/>
        <source>Scaling study: number of factors (log-spaced)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="70"/>
        <source>Scaling study per axis as well (7× the work)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="72"/>
        <source>Results (JSON)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="141"/>
        <source>holds</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="141"/>
        <source>does NOT hold</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="162"/>
        <source>{name}: the smallest variance factor must be greater than 0, got {value:g}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="165"/>
        <source>{name}: the largest variance factor must exceed {other} ({low:g}), got {value:g}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="36"/>
        <source>Sensor bound: Monte Carlo check</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="74"/>
        <source>Scaling-study plot (PNG)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="56"/>
        <source>Ground grid spacing (m)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="131"/>
        <source>{alt:g} m: {n} ground points every {spacing:g} m ({rows} × {cols}). Label error ellipse at {k:g}σ: semi-major axis max {major_max:.3g} px, median {major_median:.3g} px (tolerance r {r:g} px); anisotropy (major/minor) max {ratio_max}, median {ratio_median}.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="139"/>
        <source>{share:.1%} over {cutoff}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="141"/>
        <source>{alt:g} m: max sKLD at the deployed budget {skld:.3g} nats (threshold {thr:g}) → the linearised bound {verdict}; grid points over each sKLD cut-off: {over}; exact κ* = {kappa:.3g}.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="148"/>
        <source>unbounded (labels move along one line)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="153"/>
        <source>{name}: the ground grid spacing must be greater than 0 m, got {value:g}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/montecarlobound.py" line="58"/>
        <source>sKLD cut-offs (nats, comma-separated)</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>PartitionField</name>
    <message>
        <location filename="../processing/algorithms/partitionfield.py" line="44"/>
        <source>Partition field</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/partitionfield.py" line="56"/>
        <source>Field(s) to partition (polygons)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/partitionfield.py" line="58"/>
        <source>People surveying</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/partitionfield.py" line="60"/>
        <source>Surveying time per piece [h]</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/partitionfield.py" line="63"/>
        <source>Geotags per worker-hour</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/partitionfield.py" line="66"/>
        <source>Rate from a Survey report (JSON)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/partitionfield.py" line="69"/>
        <source>Targets per hectare</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/partitionfield.py" line="72"/>
        <source>Partitions</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/partitionfield.py" line="82"/>
        <source>AREA: the polygon layer could not be opened.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/partitionfield.py" line="87"/>
        <source>Rate from the survey report: {r:.1f} geotags per worker-hour.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/partitionfield.py" line="97"/>
        <source>AREA: row {row} of layer &apos;{layer}&apos; has no polygon; remove it or draw the field.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/partitionfield.py" line="105"/>
        <source>AREA: layer &apos;{}&apos; has no polygon to partition.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/partitionfield.py" line="116"/>
        <source>{n} field(s), {ha:.2f} ha → {k} piece(s) of about {h:.2f} h each for {p} people ({r:g} geotags per worker-hour, {t:g} targets per ha): {hours:.1f} worker-hours in all.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/partitionfield.py" line="129"/>
        <source>AREA: layer '{}' has no valid CRS; set it (Layer Properties › Source) and run again.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>PlanFlight</name>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="105"/>
        <source>Selected geotags only</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="127"/>
        <source>Capture</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="136"/>
        <source>Plan even if the points spread over more than 10 km</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="147"/>
        <source>Waypoints</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="149"/>
        <source>Route</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="159"/>
        <source>Mission files written</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="181"/>
        <source>GEOTAGS: the geotag layer could not be opened.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="184"/>
        <source>SELECTED_ONLY is set but no geotag of layer &apos;{}&apos; is selected: select the geotags of the partition to fly, or clear SELECTED_ONLY.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="195"/>
        <source>GEOTAGS: layer &apos;{}&apos; has no features: there is nothing to fly over.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="257"/>
        <source>With this camera at {alt:g} m and {v:g} m/s, one photo every {s:.2f} s gives {o:g} % forward overlap.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="319"/>
        <source>{fmt}: {files}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="329"/>
        <source>{g} geotag(s) → {w} waypoint(s) in {m} mission(s); route {km:.2f} km; estimated flight time {t:.1f} min at {v:g} m/s and {alt:g} m.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="335"/>
        <source>  mission {n}: {w} waypoint(s), {l:.0f} m, {t:.1f} min</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="67"/>
        <source>Plan the survey flight</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="211"/>
        <source>UNRESOLVED_ONLY needs a review: give REVIEW and the detection layers it judged (REVIEW_DETECTIONS).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="214"/>
        <source>The review left no cluster unresolved (uncertain, unreviewed or with conflicting verdicts): there is nothing to fly back to.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="327"/>
        <source>{u} unresolved cluster(s) of the review are targets too (waypoint field provenance: review).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="191"/>
        <source>{problem}: remove the feature or give it a position, so no target is left out of the flight.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="103"/>
        <source>Geotags</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="110"/>
        <source>Home: take-off and landing point</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="141"/>
        <source>With REVIEW: fly only to the unresolved clusters</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="107"/>
        <source>Geotag id field (empty: &apos;id&apos;)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="116"/>
        <source>Camera calibration (YAML)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="143"/>
        <source>Output CRS (empty: the site&apos;s UTM zone)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="344"/>
        <source>Surveyed area: {area}. Give CAMERA to see how much of each planned photo lies outside it (field outside_pct).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="349"/>
        <source>Surveyed area: {area}. {k} of {w} planned photo(s) see ground outside it (at the worst heading; largest share {pct:.0f} %, all photos {mean:.0f} % on average, field outside_pct): Write labels takes no negative tiles from that ground.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/planflight.py" line="121"/>
        <source>Surveyed area (polygons)</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>PrepareFieldSurvey</name>
    <message>
        <location filename="../processing/algorithms/preparefieldsurvey.py" line="29"/>
        <source>Prepare field survey</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/preparefieldsurvey.py" line="46"/>
        <source>Warn and flag the point</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/preparefieldsurvey.py" line="46"/>
        <source>Block saving</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/preparefieldsurvey.py" line="49"/>
        <source>Orthometric (QField: orthometric altitude on)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/preparefieldsurvey.py" line="49"/>
        <source>Ellipsoidal (that setting off, no grid shift)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/preparefieldsurvey.py" line="56"/>
        <source>Package folder (copy it to the device)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/preparefieldsurvey.py" line="58"/>
        <source>Project name</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/preparefieldsurvey.py" line="60"/>
        <source>Classes (comma-separated; the first is the default)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/preparefieldsurvey.py" line="62"/>
        <source>Label radius (m)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/preparefieldsurvey.py" line="64"/>
        <source>Require an RTK fixed solution</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/preparefieldsurvey.py" line="67"/>
        <source>Largest horizontal accuracy accepted (m; 0: any)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/preparefieldsurvey.py" line="70"/>
        <source>A point that fails the requirement</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/preparefieldsurvey.py" line="73"/>
        <source>Height the receiver gives QField</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/preparefieldsurvey.py" line="76"/>
        <source>Geotags surveyed before</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/preparefieldsurvey.py" line="80"/>
        <source>Points to visit</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/preparefieldsurvey.py" line="82"/>
        <source>Survey area or partitions (polygons)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/preparefieldsurvey.py" line="85"/>
        <source>Orthomosaic (copied as GeoTIFF)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/preparefieldsurvey.py" line="87"/>
        <source>Frame layer (footprints as background)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/preparefieldsurvey.py" line="91"/>
        <source>QField project (.qgz)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/preparefieldsurvey.py" line="100"/>
        <source>PROJECT_NAME: give a file name without a folder or any of / \ : * ? &quot; &lt; &gt; | (got &apos;{name}&apos;).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/preparefieldsurvey.py" line="109"/>
        <source>REVIEW needs GEOTAGS: the survey&apos;s geotags settle the clusters they match, so only the others are visited. Give the geotag layer the review was scored against.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/preparefieldsurvey.py" line="120"/>
        <source>Is there a target here? (review: {outcome})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/preparefieldsurvey.py" line="134"/>
        <source>Wrote {project}: {visits} point(s) to visit, {geotags} geotag(s) surveyed before. Copy the folder to the device and open the project in QField.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/preparefieldsurvey.py" line="145"/>
        <source>CLASSES: give at least one class name the worker picks for a geotag, comma-separated (for example &apos;burrow, nest&apos;).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/preparefieldsurvey.py" line="166"/>
        <source>Is there a target here? (from {layer})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/preparefieldsurvey.py" line="172"/>
        <source>{n} point(s) without a position left out; first: {first}</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>ProcessOdm</name>
    <message>
        <location filename="../processing/algorithms/processodm.py" line="23"/>
        <source>Process on an OpenDroneMap node</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/processodm.py" line="35"/>
        <source>Folder of the flight&apos;s images</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/processodm.py" line="37"/>
        <source>NodeODM / ClusterODM address</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/processodm.py" line="39"/>
        <source>Access token (if the node asks for one)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/processodm.py" line="46"/>
        <source>Folder for the downloaded reconstruction</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/processodm.py" line="48"/>
        <source>Solved frames</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/processodm.py" line="50"/>
        <source>Frames written</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/processodm.py" line="61"/>
        <source>Reconstruction: {path}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/processodm.py" line="41"/>
        <source>OpenDroneMap options (name=value, …)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/processodm.py" line="44"/>
        <source>Output CRS (empty: the site&apos;s UTM zone)</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>RasterBandsParametersMixin</name>
    <message>
        <location filename="../processing/parameters/raster_bands.py" line="20"/>
        <source>Bands read as red, green, blue</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/raster_bands.py" line="22"/>
        <source>Values mapped to 0–255 (not 8-bit)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/raster_bands.py" line="43"/>
        <source>The raster is not 8-bit: values mapped to 0–255 from {ranges}.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>RefinePoses</name>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="41"/>
        <source>Refine frame poses (structure from motion)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="58"/>
        <source>Features per image (at most)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="67"/>
        <source>Refined frames</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="69"/>
        <source>Report (HTML)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="71"/>
        <source>Frames registered</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="76"/>
        <source>FRAMES is required.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="83"/>
        <source>{n} frames; SIFT features at {size} px, at most {features} per image</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="109"/>
        <source>Registered {n} of {total} frames in {seconds:.0f} s ({rate:.1f} images per minute); intrinsics {intrinsics}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="114"/>
        <source>Aligned to the GNSS positions: residual RMS {rms:.3f} m</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="123"/>
        <source>{n} frame(s) keep their metadata pose (flag not_refined); first: {items}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="142"/>
        <source>OUTPUT_REPORT: cannot write {path} ({error})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="117"/>
        <source>Camera-to-ground distance of the block / (GNSS height − ground height): {ratio:.4f}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="89"/>
        <source>{n} geotags with a surveyed height: the ground plane at {h:.2f} m (ellipsoidal)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="99"/>
        <source>DEM against the frames: {check}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="105"/>
        <source>Ground of the GNSS camera-to-ground distances: {text}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="53"/>
        <source>Frames (with their images)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="55"/>
        <source>Feature image size (px, longer side)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="61"/>
        <source>Refine focal length and distortion</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/refineposes.py" line="63"/>
        <source>Geotags with surveyed heights</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>ReviewParametersMixin</name>
    <message>
        <location filename="../processing/parameters/review.py" line="60"/>
        <source>REVIEW_DETECTIONS is given without REVIEW: give the review&apos;s verdict table too, or leave REVIEW_DETECTIONS empty.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/review.py" line="65"/>
        <source>REVIEW: give the detection layer(s) the review judged (REVIEW_DETECTIONS): the verdicts name spots, the clusters come from those detections.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/review.py" line="81"/>
        <source>{layer}: {n} detection(s) without a position or score left out</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/review.py" line="91"/>
        <source>Review ({review}): {n} cluster(s) in {layers} detection layer(s); {hit} match a geotag; of the others {confirmed} confirmed real, {hard} hard negative, {conflicting} with conflicting verdicts, {uncertain} uncertain, {unreviewed} unreviewed.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/review.py" line="119"/>
        <source>{layer}: its detections were placed on {recorded}; the review&apos;s in-view test stands on the level plane here (this algorithm has no DEM, or none was given).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/review.py" line="41"/>
        <source>Their frame layers (same order)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/review.py" line="34"/>
        <source>Review verdicts (birdseye_verdicts)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/review.py" line="37"/>
        <source>Detection layers the review judged</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/review.py" line="105"/>
        <source>From the review: {targets} target(s) nobody surveyed are labelled (provenance review); {hard} hard negative(s) put their tiles first in the negative sample; no tile near one of the {unresolved} unresolved cluster(s) is written.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>ScreenCheckpoints</name>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="107"/>
        <source>ONNX checkpoints</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="109"/>
        <source>Validation flights (frame layers with their images)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="111"/>
        <source>Geotags</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="130"/>
        <source>Pixel F1: match radius (px)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="133"/>
        <source>Collapsed if the distinct-position fraction is below</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="139"/>
        <source>Checkpoint table (CSV)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="141"/>
        <source>Checkpoint table (JSON)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="143"/>
        <source>Frontier plot (PNG)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="147"/>
        <source>Healthy checkpoints</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="154"/>
        <source>CHECKPOINTS: give at least one ONNX file.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="156"/>
        <source>FRAMES: give at least one validation flight.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="165"/>
        <source>GEOTAGS: the geotag layer cannot be read.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="200"/>
        <source>{name} on {flight_name}: {skipped} frame(s) skipped (unreadable image or no ground height)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="85"/>
        <source>Screen checkpoints</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="103"/>
        <source>Method: blocks of 500 frames, threshold 0.03</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="182"/>
        <source>all</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="182"/>
        <source>of each checkpoint</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="253"/>
        <source>healthy</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="253"/>
        <source>collapsed</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="253"/>
        <source>too sparse</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="255"/>
        <source>{checkpoint}: {state}; recall_pre {recall}, gmcf_pre {gmcf}, F1 {f1_geo}, {dpf} detections per frame, review load {load}, pixel F1 {f1_pixel} (within {radius:g} px){frontier}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="255"/>
        <source> (frontier)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="103"/>
        <source>BirdsEye: whole flights, each model&apos;s threshold</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="119"/>
        <source>Preset (blocks and threshold)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="122"/>
        <source>Threshold (empty: the preset&apos;s)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="125"/>
        <source>Frames per block (0: whole flights)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="136"/>
        <source>Too sparse below (detections/frame, worst block)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="145"/>
        <source>Report (HTML)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="169"/>
        <source>HELDOUT_GEOTAGS: give the held-out flights (HELDOUT_FRAMES) too, or leave it empty.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="177"/>
        <source>validation</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="179"/>
        <source>held-out</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="182"/>
        <source>{side}: {n_blocks} block(s) of {size} frames over {n_flights} flight(s); threshold {threshold}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="264"/>
        <source>Survey density ({side}): {mean} geotags in view per frame (median {median}, {empty} of the frames see none)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="274"/>
        <source>{checkpoint}: recall {recall_v} → {recall_h} (Δ {d_recall}), GMCF {gmcf_v} → {gmcf_h} (Δ {d_gmcf}), validation → held-out</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="281"/>
        <source>Spearman's ρ of {figure}, validation vs held-out: {note}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="284"/>
        <source>Spearman's ρ of {figure}, validation vs held-out: {rho:.3f} over {n} healthy checkpoints</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="113"/>
        <source>Held-out flights (frame layers)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/screencheckpoints.py" line="116"/>
        <source>Held-out geotags (empty: Geotags)</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>SealPreregistration</name>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="76"/>
        <source>Sealed rule (JSON)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="78"/>
        <source>Seal (SHA-256)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="88"/>
        <source>CHECKPOINTS: {path} is not a file</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="120"/>
        <source>OUTPUT: cannot write {out} ({exc})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="122"/>
        <source>Sealed at {sealed_at}: {seal}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="124"/>
        <source>Record this seal somewhere you cannot edit later (an e-mail, a lab notebook, a commit): the seal proves the rule unchanged only against a copy kept elsewhere.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="45"/>
        <source>Seal a preregistered selection rule</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="85"/>
        <source>ARMS, ARM_LINES: give the arms file or typed arms, not both.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="91"/>
        <source>CHECKPOINTS: two files share a file name; arms name their checkpoint by file name, so rename one.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="97"/>
        <source>CHECKPOINTS: give at least one ONNX file (or an ARMS file).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="108"/>
        <source>Arm {name}: {checkpoint} (sha256 {model_digest}) at {operating_point}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="57"/>
        <source>ONNX checkpoints (one arm each)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="60"/>
        <source>Arms file (JSON, from Select arms)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="66"/>
        <source>Detection threshold of the checkpoints&apos; arms</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="63"/>
        <source>Or arms typed, one per line</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="70"/>
        <source>Sweep or screen JSON (recorded only)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sealpreregistration.py" line="73"/>
        <source>Note (what was chosen and why)</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>SelectArms</name>
    <message>
        <location filename="../processing/algorithms/selectarms.py" line="17"/>
        <source>Select arms (max F1, max recall, lowest review burden)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/selectarms.py" line="23"/>
        <source>Sweep (the JSON output of Sweep operating points)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/selectarms.py" line="38"/>
        <source>{name}: {checkpoint} at threshold {threshold:g}, eps {eps_m:g} m, min_samples {min_samples}, eps_pred {eps_pred_m:g} m → recall_pre {recall:.3f}, gmcf_pre {gmcf:.3f}, F1 {f1:.3f}, {dpf} detections per frame (row {row})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/selectarms.py" line="25"/>
        <source>Arms (JSON)</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>SensorBoundAlgorithm</name>
    <message>
        <location filename="../processing/algorithms/sensorbound.py" line="39"/>
        <source>Results (JSON)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sensorbound.py" line="41"/>
        <source>Report with plots (HTML)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sensorbound.py" line="108"/>
        <source>{name}: cannot create the GeoTIFF {path}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sensorbound.py" line="23"/>
        <source>Sensor bound (pose-noise budget)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sensorbound.py" line="36"/>
        <source>Grid stride (px; 1: every pixel)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sensorbound.py" line="44"/>
        <source>λ_max field (GeoTIFF)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sensorbound.py" line="99"/>
        <source>{name}: with the stride {stride} px the raster&apos;s regular grid does not reach the last pixel, so it stops at the last multiple of the stride; the JSON suprema still include the frame edges.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>SimulateCampaign</name>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="100"/>
        <source>Pose noise Σ0: x, y, z (m), roll, pitch, yaw (deg)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="103"/>
        <source>Noise off (ideal poses, altimeter and geotags)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="110"/>
        <source>Terrain</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="127"/>
        <source>Output folder</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="132"/>
        <source>Terrain model (truth/dem.tif, ellipsoidal heights; none for flat terrain)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="137"/>
        <source>Frames</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="107"/>
        <source>Platform</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="121"/>
        <source>DJI drone undistorts its JPEGs (DewarpFlag 1)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="136"/>
        <source>Frames folder</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="172"/>
        <source>Simulating seed {seed}: {n_targets} targets in a {field_width_m:g} × {field_length_m:g} m field, flown at {altitude_m:g} m, {speed_ms:g} m/s, {fps:g} frames/s.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="179"/>
        <source>TERRAIN is flat: SLOPE_DEG and RELIEF_M are ignored (choose plane or hills).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="182"/>
        <source>TERRAIN is a plane: RELIEF_M is ignored (choose hills).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="188"/>
        <source>A DJI drone: photos on the lines with {forward_overlap:.0%} forward and {effective_side_overlap:.0%} side overlap; the pose in each JPEG&apos;s metadata carries heading, tilt and height errors (truth/dji_metadata_errors.csv).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="198"/>
        <source>Wrote {n_frames} frames, {log}{n_geotags} geotags to {folder}.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="75"/>
        <source>Simulate a campaign</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="134"/>
        <source>Orthomosaic of the field (orthomosaic.tif; none without rendering)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="105"/>
        <source>Render frames and the orthomosaic</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="117"/>
        <source>Side overlap (fraction; empty: {ins:g} payload, {dji:g} DJI)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/simulatecampaign.py" line="123"/>
        <source>Geoid undulation N for altMSL (m; empty: EGM96)</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>SurveyReport</name>
    <message>
        <location filename="../processing/algorithms/surveyreport.py" line="42"/>
        <source>Survey report</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/surveyreport.py" line="65"/>
        <source>Geotags (with time_utc)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/surveyreport.py" line="67"/>
        <source>Worker field</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/surveyreport.py" line="70"/>
        <source>A gap longer than this starts a session [min]</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/surveyreport.py" line="73"/>
        <source>Partitions (polygons)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/surveyreport.py" line="76"/>
        <source>Partition id field (empty: the row)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/surveyreport.py" line="79"/>
        <source>Frame layers (one flight each)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/surveyreport.py" line="81"/>
        <source>Write labels summary.json</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/surveyreport.py" line="84"/>
        <source>Labels (empty: summary.json)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/surveyreport.py" line="87"/>
        <source>Frames with labels (empty: summary.json)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/surveyreport.py" line="90"/>
        <source>Survey report (JSON)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/surveyreport.py" line="92"/>
        <source>Survey report (HTML)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/surveyreport.py" line="101"/>
        <source>GEOTAGS: the geotag layer could not be opened.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/surveyreport.py" line="105"/>
        <source>GEOTAGS: layer &apos;{layer}&apos; has no {time} field, so the report has no capture times (fields: {fields}). Import geotags writes it from the rover&apos;s time column; the field package&apos;s geotags have it.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/surveyreport.py" line="110"/>
        <source>GEOTAGS: layer &apos;{}&apos; has no geotags: there is nothing to report.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/surveyreport.py" line="114"/>
        <source>Layer &apos;{layer}&apos; has no field &apos;{field}&apos;: its geotags are one unnamed worker&apos;s.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/surveyreport.py" line="155"/>
        <source>PARTITION_FIELD: field &apos;{}&apos; gives two partitions one id; choose a field that names each once, or leave it empty.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/surveyreport.py" line="170"/>
        <source>{g} geotag(s), {t} with a capture time, by {p} people in {s} session(s): {h:.2f} worker-hours, {rate} geotags per worker-hour; elapsed field time {e:.2f} h ({first} to {last}).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/surveyreport.py" line="178"/>
        <source>{n} geotag(s) have no capture time: counted, but left out of the rates.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/surveyreport.py" line="181"/>
        <source>{n} labels / {h:.2f} worker-hours = {r:.0f} labels per worker-hour.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/surveyreport.py" line="185"/>
        <source>{k} of {n} partition(s) hold a geotag; {out} geotag(s) lie outside every partition.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>SurveyedAreaParametersMixin</name>
    <message>
        <location filename="../processing/parameters/surveyed_area.py" line="21"/>
        <source>Surveyed area (polygons)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/surveyed_area.py" line="24"/>
        <source>Margin around the geotags&apos; hull (m)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/parameters/surveyed_area.py" line="34"/>
        <source>Surveyed area: {area}. Negative tiles only where it holds the tile&apos;s whole ground; positives anywhere.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>SweepOperatingPoints</name>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="100"/>
        <source>Geotags</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="106"/>
        <source>De-duplication grid cell (cm)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="114"/>
        <source>Credible: mean geotags per hit cluster at most</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="117"/>
        <source>Credible: mean median cluster extent at most (m)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="120"/>
        <source>Configurations (CSV)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="125"/>
        <source>Frontier plot (PNG)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="150"/>
        <source>GEOTAGS: the geotag layer cannot be read.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="243"/>
        <source>No configuration passed the credibility filter.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="76"/>
        <source>Sweep operating points</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="138"/>
        <source>CHECKPOINTS, DETECTIONS: give ONNX checkpoints (the sweep runs them over the frames) or detection layers made by Detect, not both and not neither.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="142"/>
        <source>FRAMES: give at least one frame layer.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="144"/>
        <source>FRAMES: give one frame layer per detection layer, in the same order (got {detections} detection layer(s) and {frames} frame layer(s)).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="172"/>
        <source>{name}: {n_frames} frames, {value} geotags in view</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="181"/>
        <source>{layer}: {n} detection(s) without a position or score left out</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="186"/>
        <source>Threshold axis: the thresholds the layers were detected at, {values} (THRESHOLDS is used with CHECKPOINTS only).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="236"/>
        <source>Pareto: {checkpoint}, threshold {threshold}, eps {eps_m} m, min_samples {min_samples}, eps_pred {eps_pred_m} m → recall_pre {recall_pre:.3f}, gmcf_pre {gmcf_pre:.3f}, F1 {f1_geo:.3f}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="278"/>
        <source>{checkpoint} on {flight}: {n} frame(s) skipped, e.g. {frame_id}: {reason}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="94"/>
        <source>ONNX checkpoints (run over FRAMES)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="97"/>
        <source>Or detection layers (from Detect)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="102"/>
        <source>Frame layers (one per flight or detection layer)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="110"/>
        <source>Edge buffer at the image border (px)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="122"/>
        <source>Configurations and Pareto front (JSON)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/sweepoperatingpoints.py" line="197"/>
        <source>Sweeping {n_checkpoints} checkpoint(s) × {size} configurations ({items}: threshold × eps × min_samples × eps_pred; minimum points count {counted})</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>TerrainSlopeAlgorithm</name>
    <message>
        <location filename="../processing/algorithms/terrainslope.py" line="40"/>
        <source>Altitude above the ground [m]</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/terrainslope.py" line="44"/>
        <source>Steepest slope studied [degrees]</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/terrainslope.py" line="47"/>
        <source>Results (JSON)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/terrainslope.py" line="49"/>
        <source>Contour plot (PNG)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/terrainslope.py" line="57"/>
        <source>{name}: the altitude must be greater than 0 m, got {value:g}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/terrainslope.py" line="62"/>
        <source>{name}: the steepest slope must lie between 0° and 90° (exclusive), got {value:g}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/terrainslope.py" line="78"/>
        <source>{where}: {d:.2f} m from the nadir point at {alt:g} m (ρ = {rho:.3f}) — labels stay within {tol:g} px up to a {limit:.1f}° uphill slope.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/terrainslope.py" line="102"/>
        <source>Farthest left/right edge midpoint</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/terrainslope.py" line="103"/>
        <source>Farthest top/bottom edge midpoint</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/terrainslope.py" line="104"/>
        <source>Farthest frame corner</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/terrainslope.py" line="30"/>
        <source>Sensor bound: terrain-slope study</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>TrainDetector</name>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="53"/>
        <source>Train detector (heatmap model from training labels)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="98"/>
        <source>Training time budget (minutes)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="110"/>
        <source>Random seed</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="116"/>
        <source>CPU threads for training (0: all cores)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="125"/>
        <source>Trained model (ONNX)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="127"/>
        <source>Model card (Markdown)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="128"/>
        <source>Loss curves (PNG)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="129"/>
        <source>Weights to fine-tune from (.pt)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="203"/>
        <source>none set up</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="214"/>
        <source>Training in {python} ({origin}): torch {torch}.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="251"/>
        <source>Cancelled by the user; no model was written.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="260"/>
        <source>The last checkpoint is kept: {path}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="265"/>
        <source>Wrote {model} (default threshold {threshold:g}), its model card and loss plot; training {train:.1f} s on {device}, {tiles_per_s:.1f} tiles/s; {overhead:.1f} s outside training (process start, loading tiles, validation, export; the first line came after {first:.1f} s).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="78"/>
        <source>Write-labels folders (with tiles)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="83"/>
        <source>Or one GSD for every frame (cm/px)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="92"/>
        <source>ImageNet weights of the encoder (.pth)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="95"/>
        <source>Earlier model to fine-tune (.pt, .onnx)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="118"/>
        <source>Python with PyTorch</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="45"/>
        <source>Fast (default)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="86"/>
        <source>Training preset</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="45"/>
        <source>Method (EfficientNetV2, two stages, AdamW)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="89"/>
        <source>Network (the Method preset sets its own)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="100"/>
        <source>Model resolution (cm/px; empty: automatic)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="103"/>
        <source>Validation: hold out</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="103"/>
        <source>Spatial blocks (no target shared with training)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="103"/>
        <source>Whole flights (labels folders)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="103"/>
        <source>Nothing (threshold not validated)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="203"/>
        <source>Train detector needs PyTorch, which it runs in a separate Python process; no Python with torch, onnx and OpenCV was found ({tried}). In QGIS, choose {menu} and install the group '{group}' ({build} build); or install it yourself: {command}; or name a Python that has them (parameter {parameter}, or the environment variable {variable}) — for a virtual environment: &lt;venv&gt;/bin/python -m pip install &quot;torch=={torch}&quot; &quot;torchvision=={torchvision}&quot; onnx opencv-python-headless matplotlib onnxruntime scipy</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="272"/>
        <source>Default threshold: {rule}.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="80"/>
        <source>Frame layers (GSD and pose of each frame)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="107"/>
        <source>Share of the targets held out (0–0.5)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/traindetector.py" line="113"/>
        <source>Default threshold (empty: from validation)</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>WriteLabels</name>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="99"/>
        <source>Geotags (surveyed targets)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="123"/>
        <source>Write one soft-label raster per frame</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="125"/>
        <source>Write a tiled training set (image and label tiles)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="127"/>
        <source>Tile size (px)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="130"/>
        <source>Negative tiles kept per positive tile</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="133"/>
        <source>Random seed for the negative-tile sample</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="136"/>
        <source>Write COCO-keypoints JSON</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="139"/>
        <source>Label folder</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="140"/>
        <source>Frames with label counts</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="143"/>
        <source>Geotags with frames seen</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="210"/>
        <source>GEOTAGS and FRAMES are both required.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="243"/>
        <source>{n_records} frames ({n_groups} camera(s)), {n_geotags} geotags, σ = {sigma:g} px, edge buffer {edge_buffer_px:g} px</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="260"/>
        <source>{n_steep} frame(s) lie on terrain steeper than the level plane's 10° envelope (flag steep_terrain; first: {items}): their labels drift off target — give the DEM (parameter DEM)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="266"/>
        <source>{n_no_ground} frame(s) have no ground height (no usable altimeter reading, flag no_ground_height) and get no labels; first: {items}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="78"/>
        <source>Write training labels</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="254"/>
        <source>{n} frame(s) could not be refined and keep their metadata pose (flag not_refined; first: {items}): their labels are only as good as the drone&apos;s metadata. Leave them out with a filter such as &quot;flags&quot; NOT LIKE &apos;%not_refined%&apos;</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="102"/>
        <source>Frames</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="103"/>
        <source>Soft-label σ (px)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="115"/>
        <source>Edge buffer at the image border (px)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="187"/>
        <source>σ = r / 3 = {value:g} px from {path} (SENSOR_BOUND_JSON; SIGMA_PX is not used)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="106"/>
        <source>…or σ = r/3 from a sensorbound JSON</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="109"/>
        <source>Where σ comes from</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="160"/>
        <source>SIGMA_SOURCE asks for σ measured on a label check: give MARK_CHECK (the label check Import camera solution writes from the pinned image marks).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="165"/>
        <source>σ = {value:.2f} px measured on {path}: the per-axis RMS of label − mark over {n} {kind} mark(s) (RMS u {u:.2f} px, v {v:.2f} px, largest error {max:.1f} px); SIGMA_PX and SENSOR_BOUND_JSON are not used</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="171"/>
        <source>{n} {kind} mark(s) have no label (the point falls outside its image) and are left out of σ: check them in the label check.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="175"/>
        <source>The label check has no check point with a label: σ comes from control points, which took part in the adjustment and flatter the labels.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="178"/>
        <source>σ from {n} mark(s) (fewer than {few}) is uncertain by about ±{pct:.0f} %.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="183"/>
        <source>MARK_CHECK is not used: SIGMA_SOURCE is the given σ.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="191"/>
        <source>σ = {value:g} px as given (SIGMA_PX)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="202"/>
        <source>Relief check skipped: give the targets&apos; relief (RELIEF_M) or a DEM.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="219"/>
        <source>{problem}: a target without a position may lie in any negative tile. Give it its position or remove it, then write the tiles.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="222"/>
        <source>{n} geotag(s) without a position are left out; first: {problem}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="119"/>
        <source>Target relief h (m; empty: from the DEM)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabels.py" line="112"/>
        <source>Label check (pinned marks) for a measured σ</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>WriteLabelsRaster</name>
    <message>
        <location filename="../processing/algorithms/writelabelsraster.py" line="32"/>
        <source>Write training labels on a raster (orthomosaic)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabelsraster.py" line="42"/>
        <source>Raster (orthomosaic)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabelsraster.py" line="43"/>
        <source>Geotags (surveyed targets)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabelsraster.py" line="45"/>
        <source>Soft-label σ on the ground (cm)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabelsraster.py" line="48"/>
        <source>Tile size (px)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabelsraster.py" line="50"/>
        <source>Negative tiles kept per positive tile</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabelsraster.py" line="53"/>
        <source>Random seed for the negative-tile sample</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabelsraster.py" line="58"/>
        <source>Label folder</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabelsraster.py" line="94"/>
        <source>Raster {width} × {height} px at {gsd:.2f} cm/px, bands {bands} as red, green, blue; {n} geotag(s); σ = {cm:g} cm = {px:.2f} px (label radius 3σ = {radius:.1f} px), tiles of {tile} px.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabelsraster.py" line="100"/>
        <source>σ is {px:.2f} px, under one pixel of the raster: the labels are a dot or two. Give σ in cm large enough to cover the orthomosaic's error against the survey.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/algorithms/writelabelsraster.py" line="114"/>
        <source>{labels} label(s) of {in_view} of {n} geotag(s); tiles: {positive} with a target, {negative} negative written; skipped: {near} near a target not labelled, {outside} without a target not wholly inside the surveyed area, {empty} drawn without a pixel of data; {hard} negative(s) hold a hard negative. Each tile is one frame for Train detector, which reads the raster&apos;s GSD from summary.json.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>help:clusterdetections</name>
    <message>
        <location filename="../resources/help/clusterdetections.md" line="1"/>
        <source>Turns a detection layer into clusters on the map: a burrow seen in ten frames becomes one cluster, not ten points. Detections are placed in a local metric frame (any layer CRS works, geographic included), de-duplicated on a square grid, then clustered with DBSCAN. Outputs are written in the detection layer&apos;s CRS.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/clusterdetections.md" line="3"/>
        <source>## How it works</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/clusterdetections.md" line="5"/>
        <source>- **De-duplication**: every occupied grid cell (DEDUP_CM) becomes one point at the mean position of its detections, and remembers how many detections it holds. This keeps DBSCAN fast on hundreds of thousands of detections.
- **DBSCAN** on those points: a point is a *core* point when the detections within EPS_M of it (its own included) number at least MIN_SAMPLES — or, with **Minimum points count** set to *cells* (the method&apos;s), when at least MIN_SAMPLES occupied cells lie within EPS_M. Clusters are core points linked through EPS_M plus the points within EPS_M of them; everything else is noise. A border point reachable from two clusters joins the first one found.
- **Cluster figures** are computed over each cluster&apos;s detections: centroid = their mean position; median extent = twice the median distance of the detections from the centroid (a robust diameter, m).
- With geotags, a cluster is a **hit** when an in-view geotag lies within EPS_PRED_M of one of its core points (horizontal distance). With frames, a geotag is *in view* when it projects inside at least one frame of the layer (by EDGE_BUFFER_PX), placed on the ground the detections were placed on (the detection layer&apos;s `ground` field: level plane, method&apos;s plane or DEM), as in Evaluate detections; without frames every geotag counts as in view. Detections found on a raster (Detect targets on a raster, `ground` = `raster`): the geotags in view are those on the raster&apos;s valid pixels, and MIN_SAMPLES is taken as 1 — one image shows a target once.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/clusterdetections.md" line="10"/>
        <source>## Parameters</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/clusterdetections.md" line="12"/>
        <source>- **Detections**: the output of Detect targets (fields frame_id, score; model, model_digest, threshold used when present; ground height in Z).
- **De-duplication grid cell (cm)**, default 3: detections of one target from many frames differ by 1–3 cm of projection noise; one 3 cm cell keeps a single point for near-identical repeats. By default the minimum points still count every detection in it, so the grid changes speed, not results, wherever its lines fall.
- **DBSCAN radius EPS (m)**, default 0.20 — with MIN_SAMPLES 2 and EPS_PRED 0.20 m, the configuration the method reports (to reproduce its tables exactly, also set Minimum points count to *cells*). About seven grid cells: the scattered detections of a burrow-sized target (a few cm, seen with cm-level pose noise and several cm near the frame edge) chain into one cluster, while targets more than 0.2 m apart stay apart. Where targets lie closer, lower it (the method also reports 0.10 and 0.15 m).
- **DBSCAN minimum points**, default 2: a core point needs two detections within EPS (its own included) — the spot was detected at least twice (in two frames, or twice in one); a single detection stays noise. The method also reports 5, 10 and 20: fewer false alarms, lower recall.
- **Minimum points count** (CORE_COUNT, advanced), default *Detections in the cells within EPS* (0): what the minimum points count. *Cells within EPS, one point each (the method&apos;s)* (1) counts each occupied 3 cm cell once, however many detections it holds. With well-refined poses a target&apos;s detections often all land in one cell: counted as cells it is then a single point that never reaches MIN_SAMPLES 2, and whether a target survives depends on whether its detections happen to straddle a grid line — better poses give lower recall. Use *cells* only to reproduce the method&apos;s figures.
- **Geotags** (optional): any point layer; ids from an `id` field (each geotag its own; empty or shared ids are refused), else the row number (1.., in feature order).
- **Frames** (optional): the flight&apos;s frame layer; every frame in it counts as processed.
- **Match radius EPS_PRED (m)**, default 0.20: RTK geotag error (1–2 cm), projection error near the frame edge (several cm at 10–20 m) and a rover pole set on the rim of a burrow (about 5 cm) all fit well inside 20 cm, which stays far below the spacing of distinct targets. The review dock propagates verdicts over the same 0.20 m.
- **Edge buffer (px)**, default 0: a geotag must project at least this far inside the image to count as in view.
- **Terrain model (DEM)**, **DEM heights are measured from**, **geoid undulation N (m)** (optional): with frames and geotags, needed for detections Detect placed on a DEM (give that DEM, which `dem_source` names) and refused for detections placed on a plane; see Evaluate detections.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/clusterdetections.md" line="23"/>
        <source>## Outputs</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/clusterdetections.md" line="25"/>
        <source>- **Clusters** (polygons): the convex hull of each cluster&apos;s detections grown by 3 cm (a 32-sided polygon circumscribing it), with cluster_id, centroid_x, centroid_y (layer CRS), n_detections, n_frames (distinct frames), median_extent_m (m), max_score, matched_geotag_ids (comma-separated), hit (1/0). Styled: hits green, unmatched clusters orange (review those first).
- **De-duplicated points** (optional): point_id, cluster_id (−1 = noise), core (1/0), n_detections merged into the point (what the minimum points count by default), score (the highest of theirs). Drawn as points in a cluster and noise (grey crosses).
- Counts: clusters, hit clusters, noise points.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>help:comparedetectors</name>
    <message>
        <location filename="../resources/help/comparedetectors.md" line="1"/>
        <source>Compares two detectors on one flight — typically the model before and after a round of review-driven retraining. Both detection layers are scored exactly as Evaluate detections scores them (same clustering, same matching, same local frame), the figures are set side by side, and a point layer shows what changed: which surveyed targets the new detector found or lost, and which false clusters it removed or added.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/comparedetectors.md" line="3"/>
        <source>## What changed (the `change` field of the output layer)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/comparedetectors.md" line="5"/>
        <source>- For every **in-view geotag** (Evaluate detections&apos; in-view test): **found_by_both**, **found_only_by_new**, **lost_by_new** or **missed_by_both** — &quot;found&quot; is &quot;recovered&quot; as recall counts it (within EPS_PRED_M of a core point of a cluster). Geotags out of view are in no row.
- For every **false cluster** — a cluster no in-view geotag matches, as GMCF counts it: two clusters of the two detectors are **the same spot** when a core point of one lies within EPS_PRED_M of a core point of the other. An old false cluster with no new false cluster at its spot is **false_removed**, with one **false_kept**; a new false cluster with no old one at its spot is **false_added**.
- &quot;False&quot; means unmatched by the survey, not necessarily wrong: surveys are never exhaustive. Give the review (REVIEW) to see the POST scores, which count confirmed clusters as real.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/comparedetectors.md" line="9"/>
        <source>## Parameters</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/comparedetectors.md" line="11"/>
        <source>- **Detections of the old detector (before)** and **of the new detector (after)** (DETECTIONS_OLD, DETECTIONS_NEW): two outputs of Detect targets on the same flight, one model each. A warning is given when both come from the same model file at the same threshold.
- **Frames of the flight** (FRAMES): the frame layer both detectors ran on (processed frames, the in-view test, detections per frame).
- **Terrain model (DEM)**, **DEM heights are measured from**, **geoid undulation N (m)** (optional): both layers must have been placed on one ground (a change of ground is not a change of detector; layers placed on different grounds are refused); for layers placed on a DEM give that DEM, as in Evaluate detections.
- **Geotags** (GEOTAGS): any point layer; ids from an `id` field (each geotag its own; empty or shared ids are refused), else the row number (1.., in feature order).
- **De-duplication grid cell (cm)** (default 3), **DBSCAN radius EPS (m)** (default 0.20), **DBSCAN minimum points** (default 2), **Minimum points count** (CORE_COUNT, advanced; default detections, or cells as the method counts), **match radius EPS_PRED (m)** (default 0.20), **edge buffer (px)** (default 0): as in Evaluate detections; both detectors are scored with the same values.
- **Review verdicts** (REVIEW, optional): the review dock&apos;s verdict table, as in Evaluate detections; adds gmcf_post and recall_post under each convention for both detectors.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/comparedetectors.md" line="18"/>
        <source>## Outputs</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/comparedetectors.md" line="20"/>
        <source>- **What changed** (OUTPUT): points in the new detections&apos; CRS — geotags at their surveyed position, false clusters at their centroid (the mean of their detections) — with `change`, `kind` (target or false_cluster), `geotag_id`, `cluster_old` / `cluster_new` (the clusters&apos; `cluster_id`, as Cluster detections numbers them with the same parameters) and `n_detections_old` / `n_detections_new`.
- **Comparison (JSON)** (OUTPUT_JSON): `before` and `after`, each the JSON Evaluate detections writes for that layer alone (with its name, model, model_digest and threshold); `side_by_side`, one row per figure with before, after and after − before: recall_pre, gmcf_pre, f1_geo (ratios 0–1), n_in_view, n_recovered, n_clusters, n_hit_clusters, n_false_clusters, n_detections, n_frames, detections_per_frame (detections per processed frame, the review load) and, with a review, gmcf_post and recall_post per convention; `changes`, the count of each change; the parameters (EPS and EPS_PRED in m, DEDUP in cm, edge buffer in px).
- **Report (HTML)** (OUTPUT_REPORT): the same figures side by side and the change counts.
- recall_pre and gmcf_pre before and after, and the counts of targets found only by / lost by the new detector and of false clusters removed / added, as numbers for models.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>help:detect</name>
    <message>
        <location filename="../resources/help/detect.md" line="1"/>
        <source>Runs an ONNX heatmap model over every frame of a frame layer and puts each detection on the map: a point on the ground under the pixel where the model found a target.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/detect.md" line="3"/>
        <source>For each frame, the image is resampled from the frame&apos;s own ground sample distance (GSD, from its pose and altimeter) to the resolution the model was trained at (the model&apos;s `resolution`, cm/px), so a target covers as many pixels as in training. The resampled frame is cut into overlapping tiles (tile size and overlap from the model), run through ONNX Runtime, and the tiles&apos; centres are stitched back into one heatmap per frame (probabilities 0–1). Peaks are then found: the heatmap is smoothed a little, every connected blob above the threshold gives one detection at its intensity-weighted centre (sub-pixel), and the detection is traced back through the frame&apos;s pose and calibrated lens onto the level ground under the frame (the tilt-corrected altimeter ground, as for the labels).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/detect.md" line="5"/>
        <source>The model runs on a GPU when ONNX Runtime offers one that starts; otherwise on the CPU. The log says which. Frames are processed one at a time (memory does not grow with the number of frames); the progress bar moves per frame and Cancel stops between frames.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/detect.md" line="7"/>
        <source>## Parameters</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/detect.md" line="9"/>
        <source>- **FRAMES** — a frame layer from Import flight log or Import drone images. Each frame&apos;s `image` must exist and have the size of its camera model; frames without a ground height (no altimeter reading) are skipped and listed in the log.
- **MODEL** — an ONNX heatmap model with BirdsEye metadata (see `models/README.md` in the plugin folder: `resolution`, `tile_size`, `tiles_overlap`, normalisation, `output_kind`, `default_threshold`, …). Empty: the bundled demo model, which detects the *simulated* burrows of Simulate campaign only — train your own on your labels for real fields. A Deepness segmentation model runs too (Detect targets on a raster&apos;s help, &quot;Models from and for Deepness&quot;). A model with missing or contradictory metadata is refused with the list of what is wrong.
- **THRESHOLD** — probability (0–1) a smoothed heatmap peak must exceed to become a detection. Empty: the model&apos;s `default_threshold`. Lower finds more targets and more false alarms.
- **EDGE_BUFFER_PX** — pixels of the original frame (default 0). Detections closer than this to the image border are dropped (counted in the log), matching Write labels&apos; edge buffer, where targets that close are not trained as positives.
- **OUTPUT_HEATMAPS** — optional folder: one 8-bit PNG per frame (`&lt;frame_id&gt;.png`, 255 × probability), the size of the original image, to lay over the frame or compare with the label rasters.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/detect.md" line="15"/>
        <source>## Outputs</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/detect.md" line="17"/>
        <source>- **OUTPUT** — detections, PointZ in the frame layer&apos;s CRS (Z: height of the ground point, m, measured from what the field `height_ref` says — the frame layer&apos;s reference): `frame_id`; `u`, `v` — the peak in the original (distorted) image, px, pixel (0, 0) = centre of the top-left pixel; `score` — the peak&apos;s smoothed probability (keeping detections with score ≥ t approximates a run at threshold t); `model` (file name); `model_digest` (SHA-256 of the model file, so every detection names the exact model); `threshold`.
- **DETECTION_COUNT, FRAMES_PROCESSED, FRAMES_SKIPPED, THRESHOLD_USED, MODEL_DIGEST** — for models and scripts.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/detect.md" line="20"/>
        <source>One target seen in ten frames gives ten detections; Cluster detections merges them into one target on the ground.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/detect.md" line="22"/>
        <source>A warning is given when frames are much coarser than the model&apos;s resolution (targets then look smaller than in training).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/detect.md" line="24"/>
        <source>**Terrain model (DEM)** — optional, as in Write labels: with it each detection is back-projected onto the terrain (the viewing ray meets the DEM) instead of the level plane at the altimeter depth, and frames without an altimeter reading are still placed. The DEM, its heights measured from what **DEM heights are measured from** says (ellipsoidal, mean sea level or unknown), is converted into the frames&apos; own heights (`height_ref`; with the **geoid undulation N** (m) as given, else PROJ&apos;s EGM96 grid where needed) and checked against their ground, as in Write labels; the offset found is in the log.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/detect.md" line="26"/>
        <source>**The ground travels with the detections.** Every detection records the ground it was placed on: `ground` (`level`, `method_plane` or `dem`) and, for a DEM, `dem_source` (the raster&apos;s file), `dem_datum` (ellipsoidal, msl or unknown) and `dem_n_m` (N, m). Cluster detections, Evaluate detections, Compare detectors, the sweep and the review stand on that ground; the algorithms ask for the DEM again (they refuse to score a DEM layer without it), the review dock opens the recorded file.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/detect.md" line="28"/>
        <source>**Ground model without a DEM** (advanced, GROUND_MODEL) — as in Write labels: the level ground at the tilt-corrected altimeter depth (default) or the method&apos;s plane, normal to the optical axis at the raw altimeter reading, to reproduce the method&apos;s figures. At 3° of tilt the method&apos;s plane moves detections at the frame edges by 3–14 px (the deployed camera; see Write labels); frames without a ground height are skipped, as on the level ground, and frames of a camera without a radar altimeter (DJI gimbal frames) are refused. Clusters made from these detections inherit the choice.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>help:detectraster</name>
    <message>
        <location filename="../resources/help/detectraster.md" line="1"/>
        <source>Runs an ONNX heatmap model over a raster layer — an orthomosaic from OpenDroneMap/WebODM, DJI Terra, Pix4D or a service provider, or any georeferenced image — and puts each detection on the map, with the same fields as the detections of Detect targets.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/detectraster.md" line="3"/>
        <source>The raster is resampled from its own pixel size to the resolution the model was trained at (the model&apos;s `resolution`, cm/px), so a target covers as many pixels as in training. It is read in windows of a few thousand pixels through QGIS&apos;s raster provider, never whole: a 20,000 × 20,000 px orthomosaic runs in the memory of one window. Each window is cut into the model&apos;s overlapping tiles exactly as a frame is; neighbouring windows overlap by a tile, each keeps the detections whose centre lies in its own part, and a target found by two windows on their seam is kept once (the log counts them). The progress bar moves per window and Cancel stops between windows.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/detectraster.md" line="5"/>
        <source>## Parameters</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/detectraster.md" line="7"/>
        <source>- **RASTER** — the raster, north up, in a projected CRS in metres or feet (a raster in degrees is refused: reproject it with Raster › Projections › Warp to the field&apos;s UTM zone). Pixels at the bands&apos; no-data value, or transparent in an alpha band (OpenDroneMap&apos;s RGBA orthophotos), count as no data: nothing is detected there.
- **MODEL** — an ONNX heatmap model with BirdsEye metadata, as for Detect targets, or a Deepness segmentation model (see &quot;Models from and for Deepness&quot;). Empty: the bundled demo model (simulated burrows only).
- **THRESHOLD** — probability (0–1) a smoothed heatmap peak must exceed. Empty: the model&apos;s `default_threshold`.
- **MASK** — optional polygons (any CRS): only windows that touch them are read, and only detections inside them are kept — the field, or the surveyed area.
- **EXTENT** — optional rectangle, for instance the map canvas&apos;s extent: only inside it. With MASK, inside both.
- **BANDS** (advanced) — the bands read as red, green and blue, in that order (three bands, or one band for all three). Empty: bands 1, 2, 3, or band 1 three times for a single-band raster.
- **VALUE_RANGE** (advanced) — for a raster that is not 8-bit (16-bit, floating point): the value mapped to 0 and the value mapped to 255, for every band. Empty: each band&apos;s 2 %–98 % cumulative cut over the area, from a sample of the raster (QGIS&apos;s own default stretch); the log says the ranges used.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/detectraster.md" line="15"/>
        <source>## Outputs</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/detectraster.md" line="17"/>
        <source>- **OUTPUT** — detections, PointZ in the raster&apos;s CRS, with the fields of Detect targets: `frame_id` 0 (the raster is one image); `u`, `v` — the detection&apos;s column and row in the raster, px, pixel (0, 0) = centre of the top-left pixel; `score`; `model`; `model_digest`; `threshold`; `ground` = `raster` and `dem_source` = the raster&apos;s source. An orthomosaic carries no heights: Z is 0 and `height_ref` is `unknown`.
- **DETECTION_COUNT, WINDOWS_READ, THRESHOLD_USED, MODEL_DIGEST** — for models and scripts.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/detectraster.md" line="20"/>
        <source>## What differs from detecting on frames</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/detectraster.md" line="22"/>
        <source>A frame shows each target at the drone&apos;s own resolution and from many viewpoints: Detect targets gives several detections per target, which Cluster detections merges. An orthomosaic shows each target once, resampled and blended from the frames (seams and smear where they disagree): one detection per target. **Frames or mosaic, on your own flight:** give Compare detectors the frame detections of a flight (DETECTIONS_OLD) and the detections on its orthomosaic (DETECTIONS_NEW), with the flight&apos;s frames and the survey. Both are scored over the same geotags — those in view of the frames and on the mosaic&apos;s valid pixels — and the mosaic&apos;s detections only where the frames see; each mosaic detection can be a cluster by itself, since one image shows a target once. **Cluster detections and Evaluate detections** take raster detections too: the geotags in view are those on the raster&apos;s valid pixels (the raster the layer records in `dem_source`, so keep it where it was), and each detection can be a cluster by itself (MIN_SAMPLES is taken as 1 for them, said in the log). Evaluate needs no frame layer for them. The Review clusters dock reviews them too, with chips cut from the raster (no frame layer needed).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/detectraster.md" line="24"/>
        <source>A warning is given when the raster is much coarser than the model&apos;s resolution (targets then look smaller than in training).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/detectraster.md" line="26"/>
        <source>## Models from and for Deepness</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/detectraster.md" line="28"/>
        <source>Deepness (github.com/PUTvision/qgis-plugin-deepness) is a QGIS plugin that runs ONNX models on rasters. It reads the same metadata keys for the same settings (`model_type`, `resolution`, `tile_size`, `tiles_overlap`, `standardization_mean`, `standardization_std`, `class_names`), so models cross, in part:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/detectraster.md" line="30"/>
        <source>- **A model from Train detector, in Deepness.** It loads as a *Regressor*: Deepness takes its resolution, tile size, overlap and normalisation from the file and shows the heatmap — the probability of a target at each pixel — as a raster. Deepness finds no point detections in it; for those, run the model here. Deepness has no key for the input&apos;s channel order: a model trained from an INIT model that reads BGR gets red and blue swapped there. The bundled demo model, and models written by earlier versions, accept any tile size, which Deepness&apos;s dock refuses.
- **A Deepness segmentation model, here** (and in Detect targets). A model with Deepness&apos;s keys only and `model_type` `Segmentor` runs as a heatmap: its one output channel is the target&apos;s probability, or of two channels (background, target) the second. The default threshold is its `seg_thresh` (0.5 without it, as in Deepness), the overlap 15 % when the file gives none, the tile size the input&apos;s; the log says what was used. It must give `resolution`, read three bands (red, green, blue) and output a mask of the input&apos;s size. Each blob above the threshold becomes one detection at its centre: this suits a model that segments small targets (burrows, nests), not one that outlines fields.
- **What does not cross.** Segmentation models with more classes (which one is the target?), Deepness&apos;s detection models (YOLO-style boxes), regression models without BirdsEye&apos;s keys (a measured quantity, not a probability), super-resolution and recognition models, and models that read other than three bands are refused, with a message saying which.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>help:evaluatedetections</name>
    <message>
        <location filename="../resources/help/evaluatedetections.md" line="1"/>
        <source>Scores a detector on flights with surveyed geotags: how many surveyed targets it found (recall) and how many of its clusters match a surveyed target (GMCF), before and — with review verdicts — after review. No map is needed: the scores go to a JSON file and an HTML report.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/evaluatedetections.md" line="3"/>
        <source>## Definitions (exactly as computed)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/evaluatedetections.md" line="5"/>
        <source>- Detections of all processed frames are de-duplicated on a DEDUP_CM grid and clustered with DBSCAN (EPS_M, MIN_SAMPLES, counting detections or — CORE_COUNT *cells*, the method&apos;s — occupied cells) in a local metric frame (see Cluster detections).
- Processed frames = every frame of the frame layer given (Detect ran on all of them); frames without a ground height are left out when the detections stand on a plane, as Detect skips them; on a DEM every frame counts (Detect placed them).
- A geotag is **in view** if it projects inside at least one processed frame (at least EDGE_BUFFER_PX inside the image), placed on the ground the detections were placed on — the level plane, the method&apos;s plane or the DEM, as the detection layer records it (field `ground`); on a DEM a geotag the terrain hides from a frame is not in view of it. For detections found on a raster (Detect targets on a raster, `ground` = `raster`) a geotag is in view when it lies on the raster&apos;s valid pixels (the raster the layer records), and their clusters are counted with MIN_SAMPLES 1 (one image shows a target once). Such a layer needs no frame layer: give FRAMES for the layers found on frames alone, in their order (or one per detection layer, as before).
- An in-view geotag is **recovered** if it lies within EPS_PRED_M (horizontal distance) of a **core** point of some cluster — a border point is not enough.
- A cluster is a **hit** if at least one in-view geotag lies within EPS_PRED_M of its core points. A geotag between two clusters makes both hits.
- **recall_pre** = n_recovered / n_in_view.
- **gmcf_pre** = n_hit_clusters / n_clusters: the geotag-matched cluster fraction — a lower bound on precision, not precision. Surveys are never exhaustive, so an unmatched cluster may well be a real target nobody surveyed.
- After review, with c = clusters confirmed real and not hit, and a = targets a reviewer added that are in view (the geotags&apos; in-view test) **where no cluster of the flight fired** (no core point within EPS_PRED_M) **and no geotag lies within EPS_PRED_M** — an added target near a cluster is that cluster&apos;s spot and counts through c; one near a geotag is already in n_in_view: **gmcf_post** = (n_hit_clusters + c) / n_clusters and **recall_post** = (n_recovered + c) / (n_in_view + c + a).
- **recall_post is printed &quot;≥ x&quot; only when a = 0**: then it is a lower bound on the recall over the known targets (geotags in view and confirmed clusters), since a real cluster left unconfirmed would add one to both numerator and denominator. **When a &gt; 0 it is printed as a point value**: the recall over every real target in view, under these assumptions — the reviewer&apos;s search for missed targets was exhaustive (every real target in view that nobody surveyed and the detector missed was added); every in-view geotag is one real target; every confirmed cluster is one real target, distinct from the geotags and from the other confirmed clusters; unmatched clusters not resolved confirmed_real (hard_negative, uncertain, unreviewed) are not real targets. Either way, real targets that nobody surveyed, the detector missed and the reviewer did not add are in no term: where the search for missed targets was not exhaustive, the figure overstates the detector&apos;s recall over all real targets.
- **Votes.** A cluster is resolved once over all direct and propagated judgements of the reviewed spots attached to it. **uncertain and unreviewed are abstentions, not votes**: only confirmed_real and hard_negative count, so [confirmed_real, uncertain] resolves to confirmed_real and [confirmed_real ×2, hard_negative, uncertain ×2] to confirmed_real; judgements that all abstain leave the cluster uncertain. POST scores are given under three conventions for conflicting votes: **positive-wins** (any confirmed_real wins), **majority-wins** (the side with more votes; a tie between confirmed_real and hard_negative is uncertain), **hard-negative-wins** (any hard_negative wins). The spread between them is part of the result.
- **F1**: none here. The F1 the method prints, **f1_geo** = 2 · recall · GMCF / (recall + GMCF) of pooled recall and pooled GMCF, is in Sweep operating points, Select arms and Screen checkpoints; from this tool&apos;s pooled recall_pre and gmcf_pre it is that same formula.
- **Survey density** = the in-view geotags per processed frame: for every frame, how many geotags are in view of that frame, summarised per flight and over all flights (mean, median, 10th and 90th percentiles, minimum and maximum, and the share of frames that see no geotag). It is reported beside GMCF because a cluster is a hit only where the survey put a geotag: where fewer of the real targets were surveyed, more clusters go unmatched and GMCF falls with the detector unchanged. Compare two sites&apos; GMCF only together with their survey densities.
- Several flights are pooled by **micro-averaging**: counts are summed over flights, then divided once — ratios are never averaged. A geotag in view in two flights counts once per flight.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/evaluatedetections.md" line="19"/>
        <source>## Parameters</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/evaluatedetections.md" line="21"/>
        <source>- **Detection layers**: one per flight (outputs of Detect targets).
- **Geotags**: any point layer; ids from an `id` field (each geotag its own; empty or shared ids are refused), else the row number (1.., in feature order).
- **Frame layers**: one per flight, in the same order as the detection layers.
- **De-duplication grid cell (cm)** (default 3), **DBSCAN radius EPS (m)** (default 0.20), **DBSCAN minimum points** (default 2), **Minimum points count** (CORE_COUNT, advanced; default detections, or cells as the method counts), **match radius EPS_PRED (m)** (default 0.20), **edge buffer (px)** (default 0): as in Cluster detections, whose help explains the defaults.
- **Terrain model (DEM)**, **DEM heights are measured from**, **geoid undulation N (m)** (optional): needed, and only allowed, for detection layers Detect placed on a DEM (their `ground` field says `dem`, and `dem_source` names the file): give that DEM, with the vertical reference Detect was given. A layer placed on a DEM is refused without one, naming the DEM it needs; a DEM given for a layer placed on a plane is refused, since it would change which geotags count as in view. A DEM other than the recorded one (another file or vertical reference) is warned about.
- **Review verdicts** (optional): the review dock&apos;s verdict table (fields unit_key, verdict, provenance, time, reviewer, lat, lon). The latest row per unit and provenance counts; each reviewed unit is attached to the clusters with a core point within EPS_PRED_M of its position; added targets (verdict &quot;added&quot;) count in a when they are in view and neither a cluster nor a geotag is within EPS_PRED_M.
- **Sealed selection rule** (optional): a file from Seal a preregistered selection rule. Its seal is verified first; a tampered rule, or detections from a model the rule does not name, are refused. The operating point of the arm scored then replaces the values above. A rule sealed before BirdsEye recorded what the minimum points count (its operating points have no `core_count`) still verifies, and is scored counting cells, as its arms were chosen; the log says so.
- **Arm to score** (ARM, optional): the arm&apos;s name in the sealed rule (`max_f1`, `max_recall`, `lowest_review_burden` for an arms file of Select arms). Needed when several arms share the detections&apos; checkpoint, as the method&apos;s arms often do; refused without a sealed rule.
- **Detections at the sealed threshold.** Under a sealed rule every detection layer must have been **detected at the arm&apos;s threshold** (Detect writes the threshold it ran at into every detection; a layer without it is refused). A layer detected at any other threshold is refused, not filtered: Detect makes one detection per blob of the heatmap above its threshold, so a blob whose humps meet between a lower and a higher threshold is one detection at the lower and two at the higher, and every centroid moves with the threshold — keeping a lower run&apos;s detections scored ≥ the sealed threshold is not a run at it, and a higher run never made the detections in between. Run Detect on the held-out flight with THRESHOLD = the arm&apos;s threshold, once per arm threshold.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/evaluatedetections.md" line="31"/>
        <source>## Outputs</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/evaluatedetections.md" line="33"/>
        <source>- **Scores (JSON)**: n_in_view, n_recovered, recall_pre, n_clusters, n_hit_clusters, gmcf_pre (pooled), the parameters (core_count among them), `survey_density` (pooled, and in each flight&apos;s row), one row per flight, and when reviewed a `post` block per convention (c, a, gmcf_post, recall_post_value, recall_post_kind = `lower_bound` when a = 0 or `point_value` when a &gt; 0, and recall_post as text: &quot;≥ x&quot; or &quot;x&quot;) with `review_notes` (for instance reviewed units that carry no position); with a sealed rule, a `preregistration` block (seal, sealed_at, the arm scored and its model_digest).
- **Report (HTML)**: the same as tables — the survey density per flight among them — with plots of the scores per flight and of cluster sizes (hit and unmatched).
- The pooled figures as numbers, for models.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>help:importcameras</name>
    <message>
        <location filename="../resources/help/importcameras.md" line="1"/>
        <source>Places frames with the poses and calibrated cameras a photogrammetry package solved (bundle adjustment), instead of a drone&apos;s own metadata. On a real DJI RTK flight, labels from the metadata missed the surveyed points by a median 164 px; with the same frames&apos; bundle-adjusted poses, by a median 1.8 px. The output is a frame layer like the other importers&apos;, so **Write labels**, **Detect**, the review dock and the evaluation work unchanged.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importcameras.md" line="3"/>
        <source>## Formats</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importcameras.md" line="5"/>
        <source>- **Agisoft Metashape** — the project itself (`.psx`, with its `.files` folder beside it, or a `.psz` archive; the active chunk is read), or *File › Export › Export Cameras…* (Agisoft XML). The chunk must be georeferenced (camera positions or ground control in a geographic or projected CRS); a project in a local coordinate system is refused with what to do in Metashape. Each camera&apos;s transform and one similarity — its component&apos;s, else the chunk&apos;s — give the camera&apos;s pose in geocentric coordinates. A project&apos;s photo paths find the images when **IMAGES** is empty. Calibration: `f`, `cx`, `cy` (measured from the image centre), `b1`, `b2` (affinity and skew), `k1`–`k4`, `p1`, `p2` (Metashape&apos;s p1 is OpenCV&apos;s p2 and vice versa: converted). Frame and fisheye sensors. Cameras that were not aligned are listed in the log and left out, never guessed.
- **OpenDroneMap / WebODM / OpenSfM** — `opensfm/reconstruction.json` (or the ODM project folder). ODM rewrites that file in UTM coordinates and keeps the topocentric original as `reconstruction.topocentric.json`, which is read when it lies beside it; the geographic origin comes from `reference_lla` in the file or `reference_lla.json` beside it. Camera models perspective, brown, fisheye, fisheye_opencv, radial, simple_radial.
- **COLMAP** — a sparse model folder (`cameras`, `images`, `points3D` as .bin or .txt; choose any of its files). COLMAP has no geographic frame of its own: say where the model is (**COLMAP_REFERENCE**): aligned here to the GPS tags of the images in **IMAGES** (a similarity transform; its residual is logged), already in ECEF (`colmap model_aligner --alignment_type ecef`), or in an east-north-up frame at **ENU_ORIGIN** (`lat, lon, h`). Models SIMPLE_PINHOLE, PINHOLE, SIMPLE_RADIAL, RADIAL, OPENCV, FULL_OPENCV (without the rational terms), OPENCV_FISHEYE, SIMPLE_RADIAL_FISHEYE, RADIAL_FISHEYE. COLMAP counts pixels from the image corner, OpenCV from the centre of the first pixel: converted.
- **Pix4D (PIX4Dmapper)** — `&lt;project&gt;_calibrated_camera_parameters.txt` from the project&apos;s `1_initial/params` folder (or that folder), with `&lt;project&gt;_offset.xyz` beside it. Pix4D&apos;s coordinates are in the project&apos;s output coordinate system, which these files do not name: give it as **SOLUTION_CRS** (Pix4D writes it in `&lt;project&gt;_wkt.prj` in the same folder and in the quality report); without it the file is refused. Each image&apos;s K, R and position give exactly Pix4D&apos;s own projection matrices (`_pmatrix.txt`); taken through WGS 84 and the frame&apos;s pose, points land within 0.04 px of them on a real project. Grid north and grid scale are converted (the camera turns by the meridian convergence; focal lengths take the grid&apos;s scale factor at the cameras, logged). Distortion R1, R2, R3, T1, T2 is OpenCV&apos;s k1, k2, k3, p1, p2 as Pix4D&apos;s published formula orders them; no real file with image observations has yet confirmed the signs of T1/T2 (they move this camera&apos;s corners by up to 26 px), and Pix4D calls these files experimental. Pix4D&apos;s pixels are taken to count from the image corner (as its own `.cam` file and documentation suggest): converted.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importcameras.md" line="10"/>
        <source>Files that name no geographic reference are refused with a message that says so. Every format&apos;s distortion converts exactly: checked format by format, each ground point lands within 0.01 px of where that package&apos;s own camera model puts it, over the whole frame.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importcameras.md" line="12"/>
        <source>## Heights and the ground</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importcameras.md" line="14"/>
        <source>A camera solution has no altimeter.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importcameras.md" line="16"/>
        <source>- Metashape exports and COLMAP models in ECEF or a stated ENU frame are ellipsoidal: their frames carry the flag `geotag_heights`, and **Write labels** projects each geotag at its own surveyed ellipsoidal height (the rover&apos;s `altWGS84`, or MSL + undulation). A geotag without a height goes onto the DEM if one is given, else onto a level plane at the median surveyed height of the other geotags (the flight&apos;s ground).
- OpenDroneMap/OpenSfM references and COLMAP models aligned to the images&apos; GPS carry whatever vertical reference the images&apos; GPS tags had: above mean sea level (EGM96) on DJI and other drones, with the drone&apos;s height bias; the frame layer says `height_ref` EGM96. Geotag heights would not be comparable, so their frames keep the ground the solution itself saw: the median height of its tie points in each frame&apos;s view (`ground_src` tie_points), and geotags are placed on it.
- Pix4D heights are those of the project&apos;s output coordinate system — ellipsoidal or above a geoid, as the project was set up; the files do not say which. A compound **SOLUTION_CRS** states it (e.g. `EPSG:32654+5773`: EGM96 heights); a plain projected CRS leaves them &quot;above mean sea level, geoid not named&quot; (`height_ref` msl): a DEM above mean sea level is then compared as it is, an ellipsoidal one needs the geoid undulation N. No `geotag_heights` flag. Pix4D&apos;s parameter files hold no tie points: give a DEM or **GROUND_HEIGHT_M** (metres, in the project&apos;s height reference) for footprints.
- Frames without tie points in view take the DEM, else **GROUND_HEIGHT_M** (a level plane, `ground_src` given), else — Metashape with control points — the control points&apos; median surveyed height (`ground_src` control_points); without any they get no footprint (the log says how many).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importcameras.md" line="21"/>
        <source>## Checking the labels before training (control points)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importcameras.md" line="23"/>
        <source>A Metashape project or export with markers — ground control or check points with surveyed coordinates, placed by hand in the images (*pinned* marks) — checks itself: each marker is projected into the frames it was marked in, exactly as **Write labels** projects a geotag, and the distance to the person&apos;s mark is reported (median, 90 % and largest, in pixels, with the worst points and frames). On a real Metashape project (a 15 mm camera 30 m over wheat, 6 markers, 23 marks): median 5.5 px, 90 % within 8.6 px. A label a few pixels from where a person would click is as good as manual labelling; tens of pixels means the solution or its georeference is off — fix it before training. Check points (markers whose reference is unticked in Metashape) did not take part in the adjustment and are the fairer test.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importcameras.md" line="25"/>
        <source>## Parameters</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importcameras.md" line="27"/>
        <source>- **CAMERAS** — the solution file (or folder).
- **IMAGES** — optional folder of the images, searched recursively and matched by file name, then by name without extension. Poses and intrinsics come from the solution, so labels can be written before the images are copied; frames without an image keep the solution&apos;s name.
- **GROUND_HEIGHT_M** — optional level ground (m) for frames without tie points and without a DEM.
- **COLMAP_REFERENCE**, **ENU_ORIGIN** — where a COLMAP model&apos;s frame is (see above).
- **SOLUTION_CRS** — the projected CRS (easting, northing, height in metres) a Pix4D project&apos;s coordinates are in: its output coordinate system. Needed for Pix4D, ignored for the other formats.
- **OUTPUT_CRS** — projected CRS in metres; empty: the UTM zone of the site.
- **DEM** — optional terrain model: footprints drape on it. **DEM heights are measured from** (ellipsoidal, mean sea level or unknown) and the **geoid undulation N** (m; ellipsoidal = mean sea level + N; empty: PROJ&apos;s EGM96 grid where needed) say how its heights compare with the frames&apos;, as in Write labels.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importcameras.md" line="35"/>
        <source>## Outputs</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importcameras.md" line="37"/>
        <source>- **OUTPUT** — frames, PolygonZ, with the frame-layer fields; flags `camera_solution` (and `geotag_heights` where the heights are ellipsoidal). Roll, pitch and yaw are those of a gimbal carrying the camera (pitch −90° = straight down).
- **OUTPUT_CONTROL** — the markers with surveyed coordinates as a geotag layer (PointZ, the Import geotags fields; flag `control_point` or `check_point`): give it to **Write labels** as GEOTAGS to see the markers&apos; labels. Only written when the solution has markers.
- **OUTPUT_MARK_CHECK** — one point per pinned mark, where the mark&apos;s ray meets the ground at the marker&apos;s height: `label`, `frame_id`, `image`, `u_mark`/`v_mark` (px, pixel-centre origin), `u_label`/`v_label`, `error_px`, `error_m`; green within 3 px, orange to 10 px, red beyond, grey when the marker does not project into that image.
- **FRAME_COUNT**, **NOT_ALIGNED_COUNT** — counts; **MARKS_MEDIAN_PX**, **MARKS_P90_PX** — the label check&apos;s median and 90th percentile (px).</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>help:importdjiimages</name>
    <message>
        <location filename="../resources/help/importdjiimages.md" line="1"/>
        <source>Places the frames of a drone — DJI or any other — from the images&apos; own metadata (no flight log needed): one footprint per image, drawn as an outline coloured by RTK state, with everything later steps need. Each image is read with the best its metadata holds: DJI XMP tags; else another maker&apos;s camera attitude in XMP; else EXIF GPS alone. One folder may mix them, and several cameras.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importdjiimages.md" line="3"/>
        <source>## DJI images (XMP `drone-dji:` tags)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importdjiimages.md" line="5"/>
        <source>- Position: XMP `GpsLatitude/GpsLongitude`, else EXIF GPS.
- Orientation: the gimbal angles `GimbalRoll/Pitch/YawDegree` (degrees; pitch −90° = straight down; yaw clockwise from true north). Without a gimbal yaw the flight yaw is used (flag `yaw_from_flight`); frames whose gimbal and flight yaw differ by more than 5° are flagged `yaw_mismatch`; gimbal pitch above −80° is flagged `non_nadir`.
- Depth: `RelativeAltitude` (m above the take-off point) over a level ground at the take-off height: ground height = `AbsoluteAltitude − RelativeAltitude`. On older DJI models `AbsoluteAltitude` is above mean sea level, not the ellipsoid; the depth is right because both heights come from the same source, but the absolute heights may differ from ellipsoidal ones by tens of metres. Ground that rises or falls from the take-off point changes the real footprint size.
- Distortion: `DewarpFlag` = 1 means the drone already removed the lens distortion from the JPEG. Such frames keep the focal length and principal point but get zero distortion (flag `dewarped`); undistorting them again would move every label. `DewarpFlag` 0 or absent: the image carries the lens distortion of `DewarpData` (or of the CALIBRATION).
- RTK: `RtkFlag` 50 = fixed, 34 = float, else none; `RtkStdLon/Lat/Hgt` (m) are carried to `rtk_std_lon_m`, `rtk_std_lat_m`, `rtk_std_hgt_m`.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importdjiimages.md" line="11"/>
        <source>## Other makers&apos; attitude in XMP</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importdjiimages.md" line="13"/>
        <source>- Parrot `drone-parrot:CameraRollDegree/CameraPitchDegree/CameraYawDegree`: the camera&apos;s attitude in north-east-down, read like DJI&apos;s gimbal angles (pitch −90° = straight down).
- `Camera:Yaw/Pitch/Roll` (Parrot, senseFly, MicaSense, Sentera and other Pix4D-style writers): Pix4D&apos;s convention, pitch 0° = straight down with the image top towards the yaw, pitch 90° = looking forward; senseFly&apos;s roll has the opposite sign and is negated.
- Parrot&apos;s `Camera:AboveGroundAltitude` (m, &quot;altitude above the ground&quot;) gives the depth over a level ground, like DJI&apos;s `RelativeAltitude`.
- Position from EXIF GPS, height from EXIF `GPSAltitude`; the camera and the height above ground as for EXIF-only images below.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importdjiimages.md" line="18"/>
        <source>## EXIF only (no attitude in the metadata)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importdjiimages.md" line="20"/>
        <source>- Position: EXIF GPS latitude and longitude; height: `GPSAltitude` (m above sea level; `GPSAltitudeRef` 1 = below).
- Orientation: the camera is assumed to look **straight down** with the **image top towards the direction of travel** (a drone flying nose-first), so its heading is the flight track&apos;s: the bearing from the previous to the next image of the same camera in capture-time order (the first and last image use their one neighbour; images hovering within 1 m are skipped over). Flag `attitude_from_track`; a lone image, or one with no movement around it, gets heading 0° (north) and the flag `heading_unknown`; where the track turns by more than 30° (the ends of survey lines) the flag `track_turn` marks the least sure headings. A drone flying sideways, or a camera turned across the track, breaks this assumption: check the footprints against the map.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importdjiimages.md" line="23"/>
        <source>**Height above ground** of EXIF-only images (and of XMP attitude without `AboveGroundAltitude`), best first:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importdjiimages.md" line="25"/>
        <source>- **FLIGHT_HEIGHT_M** given: the take-off ground is the median `GPSAltitude` of the camera&apos;s frames minus the flight height (flag `ground_from_flight_height`). The median keeps a stray frame shot during climb-out or landing from moving the ground of a whole flight; each camera gets its own, because each drone&apos;s GPS altitude has its own bias.
- else a **DEM**: the footprints drape on the terrain and each frame&apos;s ground height is the terrain under it (flag `ground_from_dem`, `ground_src` dem). The DEM is converted into the GPS altitudes&apos; heights (above mean sea level, EGM96); with no ground height of its own the flight cannot check the DEM&apos;s vertical reference, so choose it right.
- else the frames are imported with their ground **unknown**: flag `no_ground_height`, `ground_src` empty, no footprint, and the log says what gives them one. **Refine frame poses** does (each registered frame gets the ground its tie points see, and with GEOTAGS the nominal focal length is fixed by the surveyed ground); so does importing again with FLIGHT_HEIGHT_M or a DEM. Write labels and Detect leave such frames out unless a DEM is given.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importdjiimages.md" line="29"/>
        <source>These frames&apos; footprints are **approximate** (a nominal camera, an assumed attitude, GNSS heights that may be metres off): refine the poses (**Refine frame poses**) before **Write labels**.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importdjiimages.md" line="31"/>
        <source>## Camera</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importdjiimages.md" line="33"/>
        <source>The CALIBRATION file if given, else `DewarpData`, else `CalibratedFocalLength` with `CalibratedOpticalCenterX/Y`, else a nominal camera from EXIF (flag `approx_intrinsics`, a few per cent off): `FocalLength` (mm) with the sensor&apos;s pixel pitch (`FocalPlaneXResolution`), else the 35 mm equivalent focal length `FocalLengthIn35mmFilm`, else `FocalLength` with the sensor width of a few common drone cameras known by EXIF make and model (DJI FC300S/X/C, FC330, FC220: 6.17 mm; FC6310/S/R, Hasselblad L1D-20c: 13.2 mm). A nominal camera has no distortion and its principal point at the image centre. All frames of one camera — same make, model, serial number (XMP `CameraSerialNumber` or EXIF `BodySerialNumber`), image size and focal length (and `DewarpData`) — share one camera model; the log lists each camera once.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importdjiimages.md" line="35"/>
        <source>## Parameters</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importdjiimages.md" line="37"/>
        <source>- **IMAGES** — folder of drone JPEGs (name order gives `frame_id`).
- **CALIBRATION** — optional Kalibr or OpenCV YAML for this camera at the image size (or the original size of resized copies). Its `T_cam_imu` is replaced by the gimbal mounting.
- **OUTPUT_CRS** — projected CRS in metres; empty: the UTM zone of the site.
- **FLIGHT_HEIGHT_M** — optional: the height (m) above the take-off ground the flight was flown at, for images without a relative altitude (see above). Images with `RelativeAltitude` or `AboveGroundAltitude` ignore it.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importdjiimages.md" line="42"/>
        <source>## Outputs</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importdjiimages.md" line="44"/>
        <source>- **OUTPUT** — frames, PolygonZ, with the frame-layer fields (see Import flight log); `time_s` is EXIF DateTimeOriginal as POSIX seconds (UTC unless the image states its offset), `sync_offset_s` is empty; `height_ref` is EGM96 (heights above mean sea level) and `ground_src` says where each frame&apos;s ground came from: `takeoff` (`AbsoluteAltitude − RelativeAltitude`), `flight_height`, `dem`, or empty (unknown).
- **FRAME_COUNT, UNPLACED_COUNT** — counts. Images that cannot be placed (no GPS position, no GPS altitude, no focal length, a rotated image) are listed in the log with the file, the field and the reason.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importdjiimages.md" line="47"/>
        <source>**Terrain model (DEM)** — optional: footprints drape on the terrain instead of a level ground at the take-off height, and each frame gets its terrain slope (`terrain_slope_deg`; frames steeper than 10° are flagged `steep_terrain`). DJI&apos;s `AbsoluteAltitude` and EXIF&apos;s `GPSAltitude` are above mean sea level (EGM96, as GNSS receivers report it): the frame layer says so (`height_ref` EGM96) and every later step converts a DEM into these heights. Choose &quot;Mean sea level&quot; for an MSL DEM (no N needed), or &quot;Ellipsoidal&quot; — then N is the **geoid undulation** (m) you give, else PROJ&apos;s EGM96 grid at the site. The check looks at the whole flight once: the take-off height (the median over the frames of `AbsoluteAltitude − RelativeAltitude`, or of the ground FLIGHT_HEIGHT_M gives) must be a height the DEM&apos;s terrain has within 500 m of the frames, give or take 3 % of the flight height (±1.2 m at 40 m); the offset found is written to the log. Terrain that lies above or below the take-off point — a field 13 m below the hill you took off from — passes; a DEM whose heights are metres off every terrain around (a mean-sea-level DEM declared ellipsoidal, a wrong undulation, or a drone without RTK whose barometric `AbsoluteAltitude` is tens of metres off) is refused, naming the offset. A mix-up smaller than the site&apos;s relief cannot be told from relief. A DEM made from the same flight (OpenDroneMap&apos;s DSM, in the frames&apos; own heights) always agrees: give it as &quot;Mean sea level&quot;.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importdjiimages.md" line="49"/>
        <source>**Accuracy of the metadata.** The gimbal angles in the metadata are only as good as the aircraft&apos;s attitude and compass heading: on an RTK flight we measured headings off by up to 1.8° and a camera tilted 0.4–0.9° where the metadata said 0.1°, and heights 1.45 m low; labels from the metadata then miss their targets by tens to hundreds of pixels at 10–20 m. A heading from the flight track is rougher: on six real DJI Phantom 3 frames with their XMP removed it was 0.1–3.6° off the gimbal yaw. The positions of an RTK fix are centimetre-good. For pixel-accurate labels refine the poses by photogrammetry (**Refine frame poses**) before **Write labels**.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>help:importflightlog</name>
    <message>
        <location filename="../resources/help/importflightlog.md" line="1"/>
        <source>Gives every frame of a BirdsEye flight its pose and shows where it looked: one footprint per frame (the image border cast onto a level ground under the drone), drawn as an outline coloured by RTK state, plus the flight line. The frame layer carries everything later steps need (image path, time, position, attitude, ground height, depth, RTK state, sync offset, GSD, camera model), so Write labels and Detect need only this layer.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importflightlog.md" line="3"/>
        <source>## Parameters</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importflightlog.md" line="5"/>
        <source>- **POSE_LOG** — the BirdsEye pose log (CSV with header `time_s, lat_deg, lon_deg, height_m, qw, qx, qy, qz, rtk_status, radalt_m, radalt_snr, strobe`; WGS84 degrees, ellipsoidal metres, body FRD → NED quaternion, one row per INS message, `strobe` = 1 at each exposure), or the reference payload&apos;s `flight_data.db`.
- **IMAGES** — the image folder: its `images.csv` (`time_s, file`) if present, else files named `&lt;sec&gt;.&lt;nsec&gt;.png|jpg` (nsec = nanoseconds). Optional for `flight_data.db` (used to find the files named in `save_loc`).
- **CALIBRATION** — Kalibr camchain-imucam YAML (intrinsics, radtan distortion, `T_cam_imu`, optional `T_rad_imu` altimeter lever arm) or OpenCV YAML.
- **FPS** — camera frame rate (frames/s, default 5). Each strobe takes the nearest unpaired image within 1/FPS seconds; strobes and images left unpaired, and those sharing a timestamp, are counted and listed in the log, not silently dropped.
- **RADALT_SNR_MIN** — minimum altimeter SNR in dB (default 13). A frame whose reading is weaker takes the ground height interpolated from good readings within 1 s (flag `radalt_interpolated`); with none nearby it is kept without footprint (flag `no_ground_height`).
- **RTK_FILTER** — All frames (float and no-RTK frames flagged `rtk_float` / `rtk_none`), or RTK fixed frames only.
- **UTM_CRS** — only for `flight_data.db`: the UTM zone its `x, y` are in (the database does not store it). Its `z` is taken as ellipsoidal height and its quaternion `q, u, a, t` = (x, y, z, w) as body → NED, like the pose log.
- **OUTPUT_CRS** — projected CRS in metres for the outputs; empty: the UTM zone of the site.
- **DEM** — optional terrain model: footprints drape on it instead of the level ground. **DEM heights are measured from** (ellipsoidal, mean sea level or unknown) and the **geoid undulation N** (m; ellipsoidal = mean sea level + N; empty: PROJ&apos;s EGM96 grid where needed): the DEM is converted into the log&apos;s ellipsoidal heights and checked once against the altimeter&apos;s ground over the whole flight; the result is in the log.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importflightlog.md" line="15"/>
        <source>## Outputs</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importflightlog.md" line="17"/>
        <source>- **OUTPUT** — frames, PolygonZ (Z = ellipsoidal ground height): `frame_id` (strobe number), `image`, `time_s`, `lat`, `lon`, `height_m` (IMU, WGS84 ellipsoidal), `qw…qz`, `roll_deg`, `pitch_deg`, `yaw_deg` (true north), `ground_h_m`, `depth_m` (m), `height_ref` (what `height_m` and `ground_h_m` are measured from: `ellipsoidal` here), `ground_src` (where `ground_h_m` came from: `altimeter`, empty where the frame has none), `rtk_status` (3 fixed, 2 float, 1 none), `sync_offset_s` (image − strobe time, s), `gsd_cm` (cm/px at the image centre), `camera` (JSON), `flags`, and `rtk_std_*_m` (empty here). Written to a format with short text fields (an ESRI Shapefile keeps 254 characters), the camera model goes on in `camera_2`, `camera_3`, …; keep them with the layer. A GeoPackage keeps it whole in `camera`.
- **OUTPUT_TRACK** — the flight line (LineStringZ), split at gaps of more than 2 s, labelled with its frames, duration and length.
- **FRAME_COUNT, UNMATCHED_STROBES, UNMATCHED_IMAGES, BAD_ROWS** — counts for models.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importflightlog.md" line="21"/>
        <source>Bad rows of the pose log are left out and listed (count and the first ones, with row and field); the good rows are imported.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>help:importgeotags</name>
    <message>
        <location filename="../resources/help/importgeotags.md" line="1"/>
        <source>Turns the rover survey into a point layer on the map: one point per target, in file order, drawn as rings coloured by fix quality, the legend saying which (RTK fixed, RTK float, no RTK fix; control and check points as triangles). Give either a file or a point layer; the file may be a field survey package QField filled (its GeoPackage), whose decisions at the points to visit are added to the review they came from. The log says how the file was read: which column is the height and why, the units, any conversion, and the datum of the positions.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importgeotags.md" line="3"/>
        <source>## Files</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importgeotags.md" line="5"/>
        <source>- **BirdsEye rover CSV** (no header): `lat, lon, altWGS84, altMSL, gpsStatus, label`; degrees, metres, NMEA fix code.
- **NMEA log**: every `$..GGA` sentence with a position is one geotag; ellipsoidal height = MSL altitude + geoid separation; metres.
- **Emlid Flow export** (42 columns, Reach RS2/RS3/RS4) and the older **ReachView 3 export** (27 columns): read as they are, with no column mapping (details below).
- **Any other CSV with a header**: columns found by their names (below), or named with the column mapping.
- **Field survey package** (QField): its GeoPackage `birdseye_survey.gpkg`, or the package&apos;s `.qgz` beside it (below).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importgeotags.md" line="11"/>
        <source>## Field survey package (QField)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importgeotags.md" line="13"/>
        <source>The package BirdsEye prepares for QField, brought back from the field. Its `geotags` table is read as a point layer (below), QField&apos;s records as they are:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importgeotags.md" line="15"/>
        <source>- `fix` (QField&apos;s position quality): `Fixed RTK` → 4, `Float RTK` → 5 (flagged `rtk_float`), `DGPS` → 2, `Autonomous` → 1. `Unknown (4)`, written by some QField releases, is the code in brackets. A trailing ` - IMU active` is ignored.
- `h_acc_m`, `v_acc_m` → the accuracies; `time_utc` → `time_utc` (UTC; a time stored without a zone is UTC); `label` → `label`; `worker` → `worker`.
- Height: `h_ellipsoid` is ellipsoidal; `h_msl` is above mean sea level and converted with **GEOID_UNDULATION_M** (else EGM96), as for a CSV. The package names the field by the height reference declared for the receiver. The geometry&apos;s Z is not used then.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importgeotags.md" line="19"/>
        <source>**Decisions.** A point to visit in its `visits` table with a decision (Real target, Not a target, Cannot tell) settles the review units it came from. Each unit gets the decision as a verdict in the review&apos;s verdict log: **REVIEW_LOG**, else the review the package was made from. The reviewer is `field:&lt;worker&gt;`. All verdicts are added in one step. A unit that already holds the same decision from the same field worker is skipped, so importing a package twice adds nothing. Decided points that are not review units (from a point layer) are listed in the log, not written. A decision that is not one of the three is a warning naming its row.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importgeotags.md" line="21"/>
        <source>## Emlid Flow and ReachView 3 exports</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importgeotags.md" line="23"/>
        <source>- `Longitude`, `Latitude` → `lon`, `lat`, exactly as written. They are in the datum of the export&apos;s coordinate system (`CS name`): in North America usually NAD83(2011), about a metre from WGS 84. BirdsEye keeps them and the log names the datum: the drone&apos;s positions must come from the same datum.
- `Ellipsoidal height` → `h_ellipsoid` (and the layer&apos;s Z).
- `Elevation` → `h_msl` when the coordinate system has a vertical part (`… + NAVD88(GEOID18) height (ftUS)`): it is then an orthometric height and never taken as the ellipsoidal one. Without a vertical part (`WGS 84 / UTM zone 15N`) Emlid writes the ellipsoidal height there too, and `h_msl` stays empty.
- Units from the coordinate-system name: `(ftUS)` US survey feet (1200/3937 m), `(ft)` international feet (0.3048 m), none: metres. Heights and the elevation RMS take the vertical part&apos;s unit (without a vertical part, the horizontal part&apos;s), the lateral RMS the horizontal part&apos;s. `Antenna height units` is only the unit of the antenna height and is not used.
- `Solution status`: FIX → 4 (RTK fixed), FLOAT → 5 (RTK float), DGPS → 2, SINGLE → 1 (autonomous).
- `Lateral RMS` → `h_acc_m`, `Elevation RMS` → `v_acc_m`, both in metres.
- `Averaging start` → `time_utc` (its UTC offset applied).
- `Name` → `label`.
- `Antenna height`: Emlid&apos;s coordinates are already of the ground point, so nothing is removed again; a **POLE_HEIGHT_M** above 0 is refused for such a file.
- Easting, Northing, the base columns, DOPs and satellite counts are not used.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importgeotags.md" line="34"/>
        <source>## Other CSVs with a header: columns by name</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importgeotags.md" line="36"/>
        <source>Case, spaces, `_`, `-` and `.` are ignored; a unit at the end of a name — `alt (ft)`, `z [m]`, `ELLIPSOIDAL_M`, `[EllipsoidHeight:Meter:3]` — is that column&apos;s unit. The first name found of each kind is used.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importgeotags.md" line="38"/>
        <source>- Latitude: `lat`, `latitude`, `wgs84 latitude`; longitude: `lon`, `lng`, `long`, `longitude`, `wgs84 longitude` (decimal degrees; degrees-minutes-seconds are refused row by row).
- Ellipsoidal height: `Ellipsoidal height`, `ellipsoidal`, `Ellipsoid height`, `EllipsoidHeight`, `altWGS84`, `h_ellipsoid`, `HAE`, `final ellipsoidal`, …
- Height above mean sea level (kept as `h_msl`): `altMSL`, `h_msl`, `MSL`, `Ortho Height`, `ortho_ht`, `orthometric height`, `elevation msl`, …
- `Elevation`: orthometric when a coordinate-system column (`CS name`, `coordinate system`) has a vertical part, ellipsoidal when it has none. Without a coordinate-system column, `Elevation` — like `height`, `alt`, `altitude`, `z` — does not say what it is measured from: it is taken as the ellipsoidal height and the log says so. If it is above sea level, name it as **MSL_FIELD**.
- Fix: `Solution status`, `fix quality`, `fix id`, `fix`, `quality`, `solution`, `status`, `gpsStatus`, `SatQuality`, … holding an NMEA code (0–9) or a word: FIX, fixed, RTK fixed, fixed RTK → 4; FLOAT, RTK float → 5; DGPS, DGNSS, SBAS, PPP, RTX → 2 (corrected, but not RTK: flagged `no_rtk`); SINGLE, autonomous, standalone, nav → 1.
- Horizontal accuracy: `Lateral RMS`, `HRMS`, `H_RMS`, `horizontal accuracy`, `Rms2D`, `accuracy`, …; else √(E² + N²) of `Easting RMS` and `Northing RMS`. Vertical accuracy: `Elevation RMS`, `VRMS`, `vertical accuracy`, …
- Label: `label`, `name`, `point name`, `point`, `point id`, `class`, `code`, `description`, `remarks`.
- Capture time: `Averaging start`, `time utc`, `UtcDateTime`, `timestamp`, `datetime`, `time`. Kept when it is a date and time with its zone (`2026-05-20 10:27:09.4 UTC-05:00`, `2026-05-20T15:27:09Z`, `+02:00`), or without a zone when the column&apos;s name says UTC; other times are left empty and counted in the log.
- Units column (`units`, `height units`; values m, ft, ftUS): used only when no coordinate-system name gives the units.
- An antenna-height column (`Antenna height`, `Instrument Ht`, …) in a file other than Emlid&apos;s: the file does not say whether its heights are of the antenna or of the ground, and the log says so. Give **POLE_HEIGHT_M** if they are of the antenna.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importgeotags.md" line="49"/>
        <source>## How other rovers&apos; files map</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importgeotags.md" line="51"/>
        <source>- **Emlid Flow, ReachView 3**: no mapping (above).
- **SW Maps**, a CSV or spreadsheet export with `Latitude`, `Longitude`, `Elevation`, `Ortho Height`, `Fix ID`, `Horizontal Accuracy`, `Vertical Accuracy`, `Remarks`: no mapping. `Elevation` is SW Maps&apos; ellipsoidal height, `Ortho Height` goes to `h_msl`, `Fix ID` is an NMEA code, `Remarks` the label. Its time (`08/29/2023 13:31:48.000 EDT`) is not read. Its GeoPackage or Shapefile export is a point layer: give it as **INPUT_LAYER** and name its fields, for example HEIGHT_FIELD `elevation`, MSL_FIELD `ortho_ht`, FIX_FIELD `fix_id` as its GeoPackage names them.
- **Trimble, Leica, Topcon, Carlson** and other surveying apps: a custom export with a header holding latitude and longitude in decimal degrees reads by the names above, for example `Point, Lat, Long, Ellipsoid height, HRMS, VRMS, Solution`, or Trimble Penmap&apos;s user-defined CSV with its format line as the header (`[PointId],[Latitude:Degree:9],[Longitude:Degree:9],[EllipsoidHeight:Meter:3],[Rms2D:Meter:3],[SatQuality],[UtcDateTime]`, the unit in the brackets taken). A plain PNEZD file (point, northing, easting, elevation, description: grid coordinates only) has no latitude column and is refused. Export latitude, longitude and the ellipsoidal height as well, or load it in QGIS as a point layer in its own CRS and give it as **INPUT_LAYER**. Its Z is then taken as ellipsoidal, so give HEIGHT_FIELD only for an ellipsoidal height.
- **QField**: a BirdsEye field survey package is read as above. Another QField project&apos;s survey is a point layer (GeoPackage): give it as **INPUT_LAYER**. Its height is a field named as ellipsoidal or above mean sea level (as for a CSV), else Z, taken as ellipsoidal: that is what QField records unless its positioning settings apply a vertical grid or the device&apos;s orthometric altitude. A field named `h_acc_m`, `horizontal_accuracy`, `hrms`, … holds the horizontal accuracy (for example one filled with `@position_horizontal_accuracy`). A `fix` field (or FIX_FIELD) filled with `@position_quality_description` reads its English words (`Fixed RTK`, `Float RTK`, `DGPS`, `Autonomous`).
- **NMEA logs** of any receiver: as they are.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importgeotags.md" line="57"/>
        <source>## Parameters</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importgeotags.md" line="59"/>
        <source>- **INPUT** — geotag file (rover CSV, CSV with a header, NMEA log), or a field survey package&apos;s GeoPackage (`.gpkg`) or project (`.qgz`). Another GeoPackage is refused, naming its tables: load the table as a layer and give it as INPUT_LAYER.
- **INPUT_LAYER** — …or any point layer, in any CRS (transformed to WGS84). Its height: HEIGHT_FIELD, else a field named as ellipsoidal (`h_ellipsoid`, `altWGS84`, …), else MSL_FIELD or a field named as above mean sea level (`h_msl`, `altMSL`, …) converted with GEOID_UNDULATION_M, else Z taken as ellipsoidal. Fields with the accuracy names above are read as accuracies; `fix_quality` or `fix`, `label`, `time_utc` and `worker` by those names.
- **FORMAT** — Automatic (NMEA if the file holds GGA sentences, header CSV if the first row is not numbers, else rover CSV), or force one.
- **LAT_FIELD, LON_FIELD** — column names of a header CSV (decimal degrees); empty: found by name.
- **HEIGHT_FIELD** — column (CSV) or field (layer) of the ellipsoidal height; naming it states that it is ellipsoidal.
- **MSL_FIELD** — column or field of the height above mean sea level (orthometric); naming it states that.
- **FIX_FIELD, LABEL_FIELD** — column or field of the fix quality (NMEA code, a rover&apos;s word or QField&apos;s) and of the label; empty: found by name (for a layer only `fix_quality` or `fix`, and `label`).
- **UNITS** — unit of the heights and accuracies: from the file (default: a unit in the column&apos;s name, else the coordinate-system name, else a units column, else metres), or metres, international feet (0.3048 m) or US survey feet (1200/3937 m) for everything. The BirdsEye rover CSV and NMEA logs are in metres whatever is chosen.
- **GEOID_UNDULATION_M** — geoid undulation N at the site (metres; ellipsoidal = MSL + N). Used only for a CSV or layer that has heights above mean sea level and no ellipsoidal height. Empty: N from PROJ&apos;s EGM96 grid at each geotag; where that grid is not installed, the heights stay unknown (flag `no_height`) and the log says how to install it. EGM96 stands in for the file&apos;s own height system (NAVD88, a national geoid), which may differ from it by a metre or more. Give that system&apos;s N for better heights.
- **FIX_FILTER** — All geotags (float and no-RTK ones kept and flagged), or RTK fixed only (the others are dropped and counted).
- **MAX_H_ACCURACY_M** — optional, metres: geotags whose horizontal accuracy (`h_acc_m`) is worse are dropped and counted (**ACCURACY_DROPPED**). Geotags without an accuracy are kept, and the log counts them. A geotag the fix filter dropped is counted there only.
- **POLE_HEIGHT_M** — antenna pole height in metres, subtracted from both heights so they describe the ground (0–10 m, default 0). Refused for an Emlid export, whose heights are already of the ground.
- **OUTPUT_CRS** — projected CRS in metres for the output; empty: the UTM zone of the site.
- **REVIEW_LOG** — optional: the review GeoPackage (its verdict log) to add a field package&apos;s decisions to. Empty: the review the package was made from, when that file is still there.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importgeotags.md" line="74"/>
        <source>## Output</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importgeotags.md" line="76"/>
        <source>- **OUTPUT** — PointZ layer (Z = ellipsoidal ground height, 0 when unknown) with `id` (1.. in file order, counted before the filters, so a target keeps its id whichever geotags the filters drop), `label`, `fix_quality`, `lat`, `lon` (deg, as the file gives them), `h_ellipsoid`, `h_msl` (m), `h_acc_m`, `v_acc_m` (m, the rover&apos;s own figures; empty when unknown), `time_utc` (ISO 8601 UTC; empty when unknown), `source_row` (line of the file, or feature number of the layer), `flags`: `rtk_float`, `no_rtk`, `fix_unknown`, `no_height`, `duplicate_2cm` (within 2 cm horizontally of an earlier geotag; the earlier one is the original), and `worker` (who recorded it, from a field package; empty when unknown).
- **GEOTAG_COUNT**, **BAD_ROWS**, **NOT_FIXED_DROPPED**, **ACCURACY_DROPPED**, **DUPLICATES** — counts.
- **DECISIONS_IMPORTED** — verdicts a field package&apos;s decisions added to the review; **VISITS_UNDECIDED** — its points to visit without a decision.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/importgeotags.md" line="80"/>
        <source>Bad rows are left out and listed in the log (count and the first ones, each with file, row as an editor numbers lines, field and what was expected, in the file&apos;s unit); the good rows are imported.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>help:montecarlobound</name>
    <message>
        <location filename="../resources/help/montecarlobound.md" line="1"/>
        <source>Checks that the first-order (linearised) label covariance used by **Sensor bound** is trustworthy for your budget, the way the method runs the check: on a grid of ground points. The camera looks straight down on level ground at each altitude; the ground it sees (its footprint, out to the photo&apos;s edges) is covered by points every GROUND_SPACING_M metres (0.67 m by default), each seen at one pixel of the photo. Pose errors are drawn from the budget and applied to the camera exactly (as SE(3) motions), every ground point is projected into the moved camera, and how far its label lands from where it should gives, per point:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/montecarlobound.md" line="3"/>
        <source>- **Error ellipse**: the spread of the label&apos;s landing spots. Its **major axis** [px] is the semi-major axis at 3σ — three times the square root of the largest eigenvalue of the sampled covariance — the same 3σ your label tolerance r is drawn at, so compare it with r directly. Its **anisotropy** is the major axis divided by the minor one: 1 for a round spread, 2 when labels scatter twice as far in one direction as across it; it is unbounded when labels move along one line only (a budget with a single nonzero sigma, such as z alone).
- **sKLD** [nats]: the symmetric Kullback–Leibler divergence between the sampled covariance and the linearised one; 0 when the linear approximation is exact. The linearised bound holds when the largest sKLD over the grid is below 0.01.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/montecarlobound.md" line="6"/>
        <source>A scaling study repeats the check with every variance multiplied by factors from SCALE_MIN to SCALE_MAX, to show where the linearisation starts to break; the exact bound&apos;s κ* is marked on the plot.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/montecarlobound.md" line="8"/>
        <source>**Camera**: as in Sensor bound — a **platform preset** (camera, pose sigmas and camera mount together, e.g. *DJI RTK drone, poses from its image metadata*; see Sensor bound), a **calibration** file (Kalibr or OpenCV YAML; it overrides the typed intrinsics) or **fx, fy, cx, cy** [px] and **image width, height** [px]. Lens distortion is not used.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/montecarlobound.md" line="10"/>
        <source>- **Altitudes** [m]: heights above the ground, comma-separated; each &gt; 0.
- **Pose sigmas** (1σ): `x, y, z` in metres, `roll, pitch, yaw` in degrees (same axes as Sensor bound).
- **Camera mount**: how roll, pitch and yaw turn the camera, as in Sensor bound (default: as the method). The draws are turned into the camera by the mount&apos;s rotation, so the check also confirms which image direction each attitude error moves labels in.
- **Label tolerance r** [px at 3σ]: used to compute κ* of the exact bound for the plot, and printed beside the major axes in the log.
- **Ground grid spacing** [m]: distance between neighbouring ground points, along the photo&apos;s width and height (default 0.67 m, the method&apos;s). The grid is centred on the middle of the footprint and keeps the points inside it: at 10 m the deployed platform&apos;s 4.50 m × 2.82 m footprint holds 7 × 5 = 35 points. A finer grid costs time in proportion to its number of points.
- **sKLD cut-offs** [nats]: comma-separated; for each, the share of grid points whose sKLD is above it is reported (default 0.01, the threshold the verdict uses; add any other cut-off you judge by, e.g. `0.01, 0.1`).
- **Monte Carlo samples**: pose draws per check (default 20 000; sampling noise of the sKLD is about 3 / samples, and of a major axis about 0.5 % at 20 000).
- **Random seed**: the same seed gives the same numbers; one set of draws is reused for every factor, so the curves are smooth.
- **Scaling study**: smallest and largest variance factor (defaults 0.1 and 100) and the number of log-spaced factors (default 25). **Per axis** also scales one axis at a time with the others at the budget (seven times the work), showing which sensor breaks the linearisation first.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/montecarlobound.md" line="20"/>
        <source>## Outputs</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/montecarlobound.md" line="22"/>
        <source>- **Log**: per altitude, the number of ground points, the largest and median major axis [px] against r, the largest and median anisotropy, the largest sKLD with the verdict, and the share of points over each cut-off.
- **Results (JSON)**: per altitude `max_skld` at the budget, `linearisation_holds` (max sKLD &lt; `skld_threshold`), `kappa_exact`, the check and the scaling study. The check holds the grid (`spacing_m`, `grid_shape` as rows × columns, `footprint_m` as x and y ranges in metres from the point under the camera), a `summary` (`major_axis_px_max`, `major_axis_px_median`, `anisotropy_max`, `anisotropy_median`, `max_skld`, `fraction_over_skld` per cut-off) and one row per ground point in `points`: its ground position `x_m`, `y_m` (along the photo&apos;s width and height), its pixel `u`, `v`, `major_axis_px`, `anisotropy`, `skld` and the sampled and model covariances in px². An unbounded anisotropy or infinite sKLD is written as null. The scaling study holds `scales`, `skld_max` (the largest over the grid) and `per_axis`.
- **Plot (PNG)**: the largest sKLD over the grid against the variance factor, log–log, with a line at each cut-off, one panel per altitude (top to bottom in the order given).</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>help:partitionfield</name>
    <message>
        <location filename="../resources/help/partitionfield.md" line="1"/>
        <source>Cuts a field into pieces of about one hour of one person&apos;s surveying and shares them out, so everyone gets the same number of pieces and walks from one of their pieces straight into the next. The method splits its fields this way, into partitions of roughly one hour per person.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/partitionfield.md" line="3"/>
        <source>**The rule.** One person surveys GEOTAGS_PER_HOUR / TARGETS_PER_HA hectares an hour; a piece may hold that much times HOURS_PER_PIECE. The number of pieces is the field&apos;s area divided by that, rounded up, then rounded up to a multiple of N_PEOPLE, so no piece takes longer than HOURS_PER_PIECE. The pieces are strips of equal area cut across the field&apos;s long axis (the long side of the smallest rectangle around it), so they run the field&apos;s short way. Worker 1 gets the first block of neighbouring strips, worker 2 the next, and so on: a worker&apos;s pieces touch, and nobody crosses another&apos;s ground between pieces. In a concave field a strip may fall in two parts; its area is still its share.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/partitionfield.md" line="5"/>
        <source>## Parameters</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/partitionfield.md" line="7"/>
        <source>- **AREA** — the field(s), a polygon layer in any CRS; holes allowed. Each feature is one field, partitioned by itself; partitions are numbered on from one field to the next. A CRS in degrees is cut in the UTM zone of the field.
- **N_PEOPLE** — people surveying (default 2).
- **HOURS_PER_PIECE** — one person&apos;s surveying time for a piece [h] (default 1).
- **GEOTAGS_PER_HOUR** — geotags one person takes in a worker-hour (default 120: one every 30 s, walking to the target, setting the pole and a few seconds of RTK averaging). A placeholder: measure yours with Survey report.
- **REPORT** — a Survey report JSON (optional): its geotags per worker-hour replace GEOTAGS_PER_HOUR.
- **TARGETS_PER_HA** — targets expected per hectare (default 100, a placeholder: count a sample of your field).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/partitionfield.md" line="14"/>
        <source>## Outputs</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/partitionfield.md" line="16"/>
        <source>- **Partitions** — one polygon per piece, in the field&apos;s CRS (or its UTM zone), styled by worker: `field` (the AREA feature, 1..), `partition` (1..), `worker` (1..N_PEOPLE), `order` (the worker&apos;s walking order, 1..), `area_ha`, `expected_hours` (one person&apos;s time for the piece), `expected_geotags` (area × TARGETS_PER_HA). Give it to Survey report&apos;s AREA (PARTITION_FIELD `partition`) afterwards to compare the plan with the survey.
- **PIECES**, **AREA_HA**, **EXPECTED_HOURS** (all pieces&apos; hours together), **GEOTAGS_PER_HOUR_USED** — numbers for models and scripts.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>help:planflight</name>
    <message>
        <location filename="../resources/help/planflight.md" line="1"/>
        <source>Turns the geotags of a surveyed partition into the shortest drone flight that photographs every one of them, and writes the mission files the flight apps open. Geotags close together share one waypoint; the waypoints are ordered by a travelling-salesman solver over ground distances in metres; the route is split into several missions (one battery each) when it holds too many waypoints or takes too long, each mission starting and ending at home.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/planflight.md" line="3"/>
        <source>## Parameters</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/planflight.md" line="5"/>
        <source>- **GEOTAGS** — the geotag point layer (for example the output of Import geotags), in any CRS; points are transformed to WGS84 and checked: coordinates that cannot be degrees (a layer whose CRS says degrees but holds metres), empty geometries and points at 0°, 0° are refused with the feature named.
- **SELECTED_ONLY** — fly only the selected geotags (select the partition on the map first).
- **ID_FIELD** — field naming the geotags in the outputs; empty: the `id` field if the layer has one, else the row number (1.., in feature order; with SELECTED_ONLY still the row in the whole layer). Each geotag needs its own id: empty or shared ids are refused.
- **HOME** — take-off and landing point (optional). With it every mission flies home → waypoints → home and the route and time include those legs. Without it each mission runs from its first to its last waypoint and the flights to and from wherever the drone takes off are not counted.
- **ALTITUDE_M** — flight altitude above the ground, relative to the take-off point, in metres; 2–120 m (default 10, the method&apos;s flying height, at which the sensor bound accepts the deployed platform&apos;s pose noise; check yours with Sensor bound before flying higher or lower). The field is assumed level: a warning is given when the geotags&apos; heights vary by more than 10 % of the altitude.
- **SPEED_MS** — flight speed in m/s, 0.5–15 (default 3); the DJI KMZ needs 1–15 (DJI&apos;s WPML range).
- **MERGE_RADIUS_M** — geotags within this ground distance (metres) share one waypoint; every geotag ends up within this distance of its waypoint (default 2 m; 0 = one waypoint per geotag).
- **CAMERA** — camera calibration (Kalibr camchain or OpenCV YAML), optional. With it every geotag is also guaranteed to lie inside its waypoint&apos;s photo, at least FOOTPRINT_MARGIN_PX from the image edge, whatever the aircraft&apos;s heading: the camera is taken straight down (gimbal −90°) over level ground. When the footprint is smaller than the merge radius, the merge radius is reduced (the log says to what). The camera also gives the suggested capture interval.
- **FOOTPRINT_MARGIN_PX** — edge margin in pixels kept around each geotag in the photo (default 50).
- **SURVEYED_AREA** — polygons you draw around the ground the survey searched (optional; any polygon layer, any CRS, holes allowed). Without it the surveyed area is the convex hull of the geotags (with SELECTED_ONLY, the selected ones) grown by **SURVEY_MARGIN_M** (m, default 1 m) — the same area Write labels uses. With CAMERA, each waypoint reports how much of its photo sees ground outside the surveyed area (`outside_pct`): a target nobody surveyed may lie there, so Write labels takes no negative tiles from that ground, and a photo mostly outside it adds little to the training set.
- **HOVER_S** — hover time at each waypoint in seconds (default 2), to let the drone settle before the photo.
- **CAPTURE** — *Photo at each waypoint*, or *Timed capture*: photos at a fixed interval from the first to the last waypoint.
- **CAPTURE_INTERVAL_S** — interval of timed capture in seconds (default 2); 0 = the interval giving FORWARD_OVERLAP_PCT with the camera. With a camera the log always reports that suggested interval.
- **FORWARD_OVERLAP_PCT** — forward overlap for the suggested interval, in percent of the photo&apos;s length along the flight (default 80).
- **MAX_WAYPOINTS** — most waypoints in one mission (default 99, Litchi&apos;s limit; DJI Pilot 2 holds 65 535).
- **MAX_FLIGHT_MIN** — longest estimated flight of one mission in minutes (default 20); keep your battery reserve out of it.
- **DRONE**, **PAYLOAD** — DJI aircraft (Matrice 350 RTK or 300 RTK) and camera written into the KMZ.
- **FORCE** — plan even when the points spread over more than 10 km (usually a wrong CRS or bad rows; refused otherwise, naming the farthest point).
- **OUTPUT_CRS** — projected CRS in metres for the output layers; empty: the UTM zone of the site.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/planflight.md" line="25"/>
        <source>## Flying back to what the review left open (optional)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/planflight.md" line="27"/>
        <source>- **REVIEW** — the review dock&apos;s verdict table (`birdseye_verdicts` of the review GeoPackage), as in Evaluate detections. With it, every cluster the review left **unresolved** becomes a target of the plan, at its centroid (the mean of its detections), so the next flight or walk visits it: **uncertain** (only abstentions), **unreviewed** (nobody judged it) and **conflicting** (votes on both sides — the three conventions of Evaluate detections do not agree on it). Clusters a geotag matches are settled by the survey; confirmed and hard-negative clusters are settled by the review (Write labels uses them).
- **REVIEW_DETECTIONS** — the detection layer(s) the review judged (outputs of Detect targets); **REVIEW_FRAMES** — their frame layers, one per detection layer, in the same order. The clusters are made and matched to the geotags (all of GEOTAGS, selected or not) exactly as Evaluate detections does.
- **DEDUP_CM** (cm, default 3), **EPS_M** (m, default 0.20), **MIN_SAMPLES** (default 2), **CORE_COUNT** (default detections), **EPS_PRED_M** (m, default 0.20), **EDGE_BUFFER_PX** (px, default 0) — advanced: the clustering and matching the review was scored with (the review dock&apos;s values); a verdict attaches to the clusters with a core point within EPS_PRED_M of its position.
- **UNRESOLVED_ONLY** — fly only to the unresolved clusters, not to the geotags (default: both). Refused without a review, or when the review left nothing unresolved.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/planflight.md" line="32"/>
        <source>## Outputs</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/planflight.md" line="34"/>
        <source>- **OUTPUT_WAYPOINTS** — PointZ layer (Z = altitude) with `mission`, `order` (1.. within the mission), `altitude` (m, relative to take-off), `geotag_count`, `geotag_ids` (`;`-separated; an unresolved cluster is named `&lt;detection layer&gt;#&lt;cluster id&gt;`), `max_offset_m` (ground distance to its farthest geotag), `lat`, `lon` (WGS84 degrees, as in the mission files), `provenance` (where its targets came from: `survey`, `review`, or `review;survey` when both share the waypoint) and `review_outcomes` (`conflicting`, `uncertain`, `unreviewed`, `;`-separated; empty for geotags) and `outside_pct` (with CAMERA: the share of the photo, in % of its pixels, whose ground lies outside the surveyed area, at the worst heading, the camera straight down over level ground; empty without CAMERA).
- **OUTPUT_ROUTE** — one line per mission, closed at home when HOME is given, with `mission`, `waypoints`, `length_m` and `est_time_min`.
- **OUTPUT_KMZ** — DJI Pilot 2 route (WPML: `wpmz/template.kml` and `wpmz/waylines.wpml`): heights relative to take-off, the aircraft faces along the route and stops at each waypoint, gimbal at −90°, hover and a photo at each waypoint or a timed capture over the whole route, return home at the end (RTH height = flight altitude: check obstacles).
- **OUTPUT_PLAN** — QGroundControl plan: take-off, speed, gimbal −90°, waypoints (relative altitude, hover as hold time), a photo after each waypoint or an interval capture started before the first and stopped after the last, return to launch.
- **OUTPUT_LITCHI** — Litchi CSV (altitudes relative to take-off, gimbal −90°, &quot;stay for&quot; and &quot;take photo&quot; actions or a photo interval). Litchi keeps mission settings (finish action, heading mode) in the app: set them after importing.
- **OUTPUT_KML** — all missions in one KML for Google Earth: a folder per mission with its route and waypoints.
- With several missions, each mission file gets a suffix: `survey_m1.kmz`, `survey_m2.kmz`, … (the KML holds them all). **MISSION_FILES** lists every file written.
- **ROUTE_LENGTH_M**, **FLIGHT_TIME_MIN**, **WAYPOINT_COUNT**, **MISSION_COUNT**, **GEOTAG_COUNT**, **UNRESOLVED_COUNT** (the review&apos;s unresolved clusters flown to) — the summary, also written to the log with one line per mission, and a line on the surveyed area: how many photos see ground outside it, the largest share and the mean (a warning when a photo is half outside or more).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/planflight.md" line="43"/>
        <source>**Flight-time estimate**: climb at 3 m/s and descent at 2 m/s, each leg flown from standstill to standstill with 2 m/s² acceleration, the hover time, and 1 s per photo at each waypoint. Wind is not included.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/planflight.md" line="45"/>
        <source>**A single geotag** (or geotags that all merge into one waypoint) is a valid one-waypoint mission: the layers, the QGroundControl plan and the KML are written. DJI Pilot 2 and Litchi need at least two waypoints, so asking for those files is refused with a message; missions are otherwise split so that each holds at least two waypoints whenever the limits allow.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>help:preparefieldsurvey</name>
    <message>
        <location filename="../resources/help/preparefieldsurvey.md" line="1"/>
        <source>Writes a folder QField opens as it is (the layout QFieldSync&apos;s &quot;package for QField&quot; makes): a project `&lt;name&gt;.qgz`, one GeoPackage `birdseye_survey.gpkg` beside it and, when given, a copy of the orthomosaic. In the field the worker records each target with an RTK receiver: QField fills the position, the fix, the accuracies and the capture time from the receiver, checks the accuracy requirement, and Import geotags reads the records back. Points to visit (a review&apos;s unresolved clusters, or any point layer) come with a question; the worker records the decision there.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/preparefieldsurvey.md" line="3"/>
        <source>## Parameters</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/preparefieldsurvey.md" line="5"/>
        <source>- **OUTPUT_FOLDER** — the package folder; copy it whole to the device. A folder that already holds a package (the project, the GeoPackage or the orthomosaic copy of this name) is refused: a package that went to the field holds the worker&apos;s records, so it is never overwritten.
- **PROJECT_NAME** — the project&apos;s file name, without `.qgz` (default `birdseye_survey`).
- **CLASSES** — the classes the worker picks from for each geotag, comma-separated (default `target`); the first is preselected. At least one is needed.
- **LABEL_RADIUS_M** — the label radius in metres written with each geotag (`radius_m`; default 0.05 m, at least 0.005 m): how far from the recorded point the target&apos;s edge may lie.
- **REQUIRE_RTK_FIXED** — a geotag needs an RTK fixed solution (default on). QField&apos;s &quot;Fixed RTK&quot; counts, and so does &quot;Unknown (4)&quot;, which some QField releases write for a fixed solution.
- **MAX_H_ACCURACY_M** — the largest horizontal accuracy accepted, in metres (default 0.05 m; 0: no limit). A point without an accuracy fails the limit.
- **ACCURACY_ENFORCEMENT** — what QField does with a point that fails the requirement: *Warn and flag the point* (default: QField warns, the point is saved and drawn red) or *Block saving* (QField does not save it until the receiver does better).
- **HEIGHT_REFERENCE** — what height the receiver gives QField, which decides the height field: *Orthometric* (default; field `h_msl`: QField&apos;s &quot;Use orthometric altitude from device&quot; is on) or *Ellipsoidal* (field `h_ellipsoid`: that setting off and no vertical grid shift).
- **GEOTAGS** — geotags surveyed before (optional; any point layer, read as every algorithm reads geotags). They are shown read-only as &quot;Surveyed before&quot;, so the worker sees what is recorded already, and they are kept out of the new records Import geotags reads. Needed with REVIEW.
- **VISIT_POINTS** — any point layer of points to visit (optional), each named by its `id` field, else its row.
- **AREA** — the survey area or its partitions (optional polygons, any CRS), drawn as outlines with their attributes (a `partition` field labels them).
- **BACKGROUND** — the orthomosaic (optional raster), copied into the folder as `&lt;name&gt;_orthomosaic.tif` (a GeoTIFF is copied as it is; another raster file is written out as GeoTIFF; a web or tile service is refused: QField would need the network).
- **FRAMES** — a frame layer (optional); its footprints, with `frame_id`, are the background when there is no orthomosaic.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/preparefieldsurvey.md" line="19"/>
        <source>## Points a review left open (optional)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/preparefieldsurvey.md" line="21"/>
        <source>- **REVIEW** — the review dock&apos;s verdict table (`birdseye_verdicts`). Every cluster the review left **unresolved** (uncertain, unreviewed, conflicting) becomes a point to visit at its centroid, with the review units its verdicts attach to; clusters a geotag of GEOTAGS matches are settled by the survey. Refused without GEOTAGS.
- **REVIEW_DETECTIONS** — the detection layer(s) the review judged; **REVIEW_FRAMES** — their frame layers, in the same order.
- **DEDUP_CM** (cm, default 3), **EPS_M** (m, default 0.20), **MIN_SAMPLES** (default 2), **CORE_COUNT**, **EPS_PRED_M** (m, default 0.20), **EDGE_BUFFER_PX** (px, default 0) — advanced: the clustering and matching the review was scored with, as in Plan the survey flight.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/preparefieldsurvey.md" line="25"/>
        <source>## What it writes</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/preparefieldsurvey.md" line="27"/>
        <source>- **geotags** — the worker&apos;s records (points with height, WGS84): `label`, the height field (`h_msl` or `h_ellipsoid`, from QField&apos;s altitude), `radius_m`, `note`, `worker` (the QFieldCloud user, else the device&apos;s user name) and the receiver&apos;s `fix`, `h_acc_m`, `v_acc_m` (m), `pdop`, `hdop`, `vdop`, `n_sats`, `averaged`, `source` and `time_utc` (UTC), filled when the point is added and read-only in the form. Points that fail the requirement are red, the others green.
- **visits** — the points to visit: `visit_id` (a cluster&apos;s `&lt;detection layer&gt;#&lt;cluster id&gt;`, or the layer&apos;s id), `origin` (`review:&lt;outcome&gt;` or `layer:&lt;name&gt;`), `unit_keys` (the review units, a JSON list), `question`, and what the worker fills in: `decision` (Real target, Not a target, Cannot tell; empty = not visited), `note`, and the same GNSS fields, filled each time a decision is saved (with the crosshair snapped to your position, as for a geotag). Orange until decided. The points cannot be moved.
- **surveyed_before**, **survey_area**, **frame_footprints** and the orthomosaic — read-only background.
- **birdseye_package** — the package&apos;s settings (classes, label radius, accuracy requirement, height reference, the review log).
- **PROJECT** — the project&apos;s path; **VISIT_COUNT** — points to visit; **GEOTAG_COUNT** — geotags surveyed before.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/preparefieldsurvey.md" line="33"/>
        <source>The project opens in the site&apos;s UTM zone on the area, visits and geotags, with paths relative to its folder; its description tells the worker what to do.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/preparefieldsurvey.md" line="35"/>
        <source>## In QField</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/preparefieldsurvey.md" line="37"/>
        <source>1. Connect the receiver (QField settings › Positioning: the external RTK receiver over Bluetooth, or the device&apos;s own with its NTRIP corrections).
2. Set the height as HEIGHT_REFERENCE says: for *Orthometric*, &quot;Use orthometric altitude from device&quot; on; for *Ellipsoidal*, off, and no vertical grid shift.
3. Add each geotag with the crosshair snapped to your position (the GNSS button), not by tapping the map: only then are the position variables (`@position_*`) filled, and with them the GNSS fields. Wait for the fix the requirement asks for before saving.
4. At a point to visit, open it, pick the decision and save, still snapped to your position: the visit records who decided, when, and with what fix.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>help:processodm</name>
    <message>
        <location filename="../resources/help/processodm.md" line="1"/>
        <source>Sends a flight&apos;s images to an OpenDroneMap node — NodeODM on a workstation, ClusterODM in front of several, or the processing node of a WebODM — waits while OpenDroneMap reconstructs them, downloads only the camera solution (`opensfm/reconstruction.json`, its topocentric copy and `reference_lla.json`, not the orthophoto or meshes) and imports it like **Import camera solution**. For a season of flights that outgrows this computer&apos;s structure from motion.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/processodm.md" line="3"/>
        <source>## Parameters</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/processodm.md" line="5"/>
        <source>- **IMAGES** — the flight&apos;s images (JPEG, TIFF, PNG, DNG). Add a `gcp_list.txt` to the folder on the node&apos;s side if you surveyed ground control.
- **NODE_URL** — the node&apos;s address, e.g. `http://localhost:3000` (NodeODM&apos;s default port) or a ClusterODM at port 3000; **TOKEN** — its access token, if it has one.
- **ODM_OPTIONS** — OpenDroneMap options as `name=value` pairs, e.g. `feature-quality=high, min-num-features=12000`; empty: the node&apos;s defaults.
- **OUTPUT_FOLDER** — where the downloaded reconstruction is kept (import it again later with Import camera solution).
- **OUTPUT_CRS** — projected CRS in metres; empty: the UTM zone of the site.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/processodm.md" line="11"/>
        <source>## Outputs</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/processodm.md" line="13"/>
        <source>- **OUTPUT** — the solved frames (flag `camera_solution`). OpenDroneMap georeferences from the images&apos; GPS tags (or ground control), in their vertical reference: geotags are placed on the ground the reconstruction&apos;s tie points show (see Import camera solution).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/processodm.md" line="15"/>
        <source>Progress: upload 0–20 %, processing on the node 20–70 % (the node&apos;s own estimate), download and import after. **Cancel**, at any stage, cancels the task on the node and removes it there: during the upload it returns at once, stops sending images and removes what arrived (NodeODM has no call to drop an unfinished upload, so BirdsEye commits it and removes the task at once); during the download it also deletes the partial archive. A node that cannot be reached, or a task that fails there, is reported with the node&apos;s message; the task&apos;s full console output is on the node.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>help:refineposes</name>
    <message>
        <location filename="../resources/help/refineposes.md" line="1"/>
        <source>Moves every frame to the pose photogrammetry finds for its image, so that labels land on their targets. A drone&apos;s metadata places a frame to a few metres and degrees (on a real DJI RTK flight: headings off by up to 1.8°, the camera tilted 0.4–0.9° where the metadata said 0.1°, heights 1.45 m low; labels a median 164 px off); the same frames with bundle-adjusted poses put the labels a median 1.8 px from their marks.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/refineposes.md" line="3"/>
        <source>## How</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/refineposes.md" line="5"/>
        <source>1. SIFT features on every image (COLMAP, through the `pycolmap` package), extracted on a copy downscaled to **MATCH_SIZE_PX** on its longer side and at most **MAX_FEATURES** per image; the features are scaled back, so the poses are for the full images. A downscaled image is not doubled again for SIFT&apos;s first octave (COLMAP&apos;s default), which would cost 4× the time to chase the detail the downscaling removed.
2. Matching: every pair of images for blocks of up to 60 frames, else each image with its 20 nearest neighbours by the metadata positions.
3. Incremental mapping. A flat nadir block sees only the ratio of focal length to flying height, and a wrong focal length with GNSS-fixed camera heights scales every label (on 18 real DJI frames the self-calibrated focal came out 2,777 px where the lens says about 2,340 px). So:
   - a **calibrated** camera (DewarpData, a calibration file, an earlier solution) stays **fixed**, unless **REFINE_INTRINSICS** is ticked (only when relief, oblique views or ground control determine the focal length);
   - a **nominal** camera (flag `approx_intrinsics`: a focal length from EXIF, no calibration) is estimated — one focal length and radial distortion k1, k2, principal point fixed — and its focal length is then **fixed by the flying height**, camera by camera: the block is scaled from the horizontal distances between the GNSS positions, so a focal length k times too long shows as camera-to-ground distances k times too long. BirdsEye compares the block&apos;s camera-to-ground distance (camera height minus the median height of its tie points) with GNSS height minus a ground height, divides the focal length by that ratio and adjusts the block again, at most ×1.5 per pass and up to six passes. A pass whose adjustment does not converge, leaves a pose or point that is not a number, raises the mean reprojection error by more than 0.5 px or puts observations behind their cameras is undone: the block of the pass before is kept and the report says why. A ratio outside 0.5–2 means the heights or the ground are wrong rather than the focal length; the nominal focal length is then kept, as it is where fewer than two registered frames have a ground at least 3 m below them.
   - **Which ground.** The frames&apos; own ground (DJI: the take-off point, AbsoluteAltitude − RelativeAltitude; EXIF-only images: camera height minus **FLIGHT_HEIGHT_M** given at import) or the ground the **GEOTAGS** survey (their median height). The geotags&apos; heights are ellipsoidal, a DJI drone&apos;s above mean sea level (EGM96): they are converted first, with **GEOID_UNDULATION_M** when given, else PROJ&apos;s EGM96 grid (if neither is there, the run stops and says how to install the grid). The rule, per camera: frames with an RTK fix (at least half of them) use the surveyed ground, their absolute heights being good to centimetres; frames without one use their own ground — a barometric or single-point AbsoluteAltitude can be tens of metres off (six real DJI Phantom 3 frames from Brighton Beach, on Lake Superior, put their take-off at 158.5 m, where the shore is at about 183 m), but their take-off height carries the same offset, which cancels in camera height minus take-off height, while RelativeAltitude is good; frames without a ground of their own (EXIF-only images imported without a flight height) use the surveyed one. With a **DEM**, its terrain in each frame&apos;s view (the median of a grid of rays cast from the metadata pose, like the tie points&apos; median the block&apos;s distance is measured to) comes first where it covers at least half of a camera&apos;s frames: it is the ground under each frame, where the take-off point and the geotags&apos; plane are one height for the site. The DEM is converted into the frames&apos; heights and checked against their ground first, as in Write labels; a DEM made from an independent survey (lidar) suits this best — one made by photogrammetry from the same images (OpenDroneMap&apos;s DSM) carries that reconstruction&apos;s own focal length in its heights. Frames whose heights are in an unknown reference cannot be compared with geotags and keep their own ground, said so. The report and the log give both grounds and how far apart they are (a large difference is an offset of the drone&apos;s heights, or terrain under the frames that far from the take-off point), and warn when the ground used is only the take-off point: terrain under the frames above or below it changes the focal length by that difference over the flying height (4 m at 40 m: 10 %).

   The report says which was done, with the focal lengths (px) and the final ratio of the block&apos;s to the GNSS camera-to-ground distance (1 when they agree). On the six real Brighton Beach Phantom 3 frames: nominal 2,222 px, the bundle adjustment alone 1,690 px, fixed 2,333 px (what the 3.61 mm lens on its 6.19 mm sensor gives), all six registered at 0.58 px; with geotags at the take-off ground&apos;s ellipsoidal height, the same within 1 % whether N is given as −10 or +20 m or taken from the EGM96 grid.
4. The reconstruction is aligned to the frames&apos; GNSS positions by a similarity transform, each frame weighted by its accuracy (1/σ², σ from DJI&apos;s `RtkStdLon/Lat/Hgt`, else 3 cm for an RTK fix, 0.5 m float, 3 m without RTK). When the cameras lie on one flight line (or drift sideways by less than their GNSS noise can resolve), positions cannot fix the rotation about that line: the metadata attitudes fix it. Attitudes that contradict the others by more than 15° are left out of that and named in the report (twelve other Brighton Beach frames, two lines of six, log one line&apos;s heading 180° off its images; averaged in, they turned the block upside down). The fit is robust: a frame whose position disagrees with the block by more than 5× the median residual (and 5 σ) is left out, the fit is redone on the others until that set no longer changes, and the frame is named in the report.
5. Each registered frame&apos;s ground becomes the median height of the tie points it observes (a level plane through what the camera saw, in the frames&apos; own vertical reference; field `ground_src` `tie_points`), frames without a ground of their own included; frames with fewer than 20 tie points keep their ground. The refined layer keeps the input&apos;s height reference (`height_ref`).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/refineposes.md" line="16"/>
        <source>It never silently replaces a pose: frames it cannot register (image missing, too few matches, a separate block) keep their metadata pose, get the flag `not_refined` and are listed with the reason.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/refineposes.md" line="18"/>
        <source>## Parameters</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/refineposes.md" line="20"/>
        <source>- **FRAMES** — a frame layer whose `image` field names the image files (Import drone images writes the absolute paths).
- **MATCH_SIZE_PX** — longer side for feature extraction (px, default 2,000). Memory grows with its square: at 2,000 px a run on 4000 × 2250 images peaked at 0.5 GB.
- **MAX_FEATURES** — features per image (default 8,192).
- **REFINE_INTRINSICS** — see step 3.
- **GEOTAGS** — optional point layer of surveyed targets; their ellipsoidal heights (m; an `h_ellipsoid` field, as Import geotags writes, else the points&apos; Z) place a level ground (their median), converted into the frames&apos; height reference. It fixes a nominal camera&apos;s focal length for frames with an RTK fix or without a ground of their own, and is compared with the others&apos; own ground (step 3).
- **DEM**, **DEM heights are measured from** — optional terrain model: the ground under each frame for a nominal camera&apos;s focal length (step 3), and the refined footprints drape on it.
- **GEOID_UNDULATION_M** — optional: the geoid undulation N at the site (m; ellipsoidal = mean sea level + N), used to convert the geotags&apos; heights, and a DEM&apos;s, into mean-sea-level frames&apos; heights. Empty: N from PROJ&apos;s EGM96 grid (DJI and EXIF heights are EGM96).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/refineposes.md" line="28"/>
        <source>## Outputs</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/refineposes.md" line="30"/>
        <source>- **OUTPUT** — the frame layer with refined poses (same fields as its input, flags `refined` / `not_refined`), plus `registered`, `reprojection_rms_px` (px), `n_points` (tie points), `position_change_m` (m) and `rotation_change_deg` (°) (how far the metadata pose was off) and `alignment_residual_m` (m). A refined nadir frame&apos;s `roll_deg, pitch_deg, yaw_deg` are in the gimbal&apos;s order (yaw, roll, pitch), so its heading stays in yaw and roll stays small when the camera is a fraction of a degree off the vertical.
- **OUTPUT_REPORT** — HTML: registered and not registered frames with the reason, reprojection errors (px), the alignment&apos;s residual (m), the intrinsics (focal lengths in px per camera, the camera-to-ground check), the ground of each camera (own, surveyed and the DEM&apos;s terrain, their differences, which was used and why, the warning), images per minute.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/refineposes.md" line="33"/>
        <source>**Speed.** On 2 CPU cores (shared): the six real 4000 × 2250 Brighton Beach frames in about 14 s (25 images per minute), all six registered at 0.58 px with the camera estimated. A season of flights outgrows a laptop: process it on an OpenDroneMap node (**Process on an OpenDroneMap node**, or WebODM and then **Import camera solution**).</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>help:review</name>
    <message>
        <location filename="../resources/help/review.md" line="1"/>
        <source>Review detections beside the survey (BirdsEye ▸ Review clusters). Surveys are never exhaustive: a cluster with no geotag nearby may be a real target nobody surveyed, and only a person looking at the frames can tell. The dock walks you through the clusters with the frames that saw them and the map, records your verdicts, and shows the scores before and after review.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/review.md" line="3"/>
        <source>## Setup</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/review.md" line="5"/>
        <source>- **Detections**: one or more outputs of Detect targets over one flight (for instance two checkpoints, or two thresholds). They are reviewed together: detections of all the layers are pooled, de-duplicated on the grid cell and clustered with DBSCAN exactly as Cluster detections does, so each spot on the ground is one **review unit**, judged once, whichever model fired there. The list and the log keep which layers fired at each unit.
- **Frames**: the flight&apos;s frame layer (Import flight log or Import drone images); the image chips are cut from its images. Detections found on a raster (Detect targets on a raster) need none: the choice is then greyed out.
- **Geotags**: the survey points.
- **Verdict log**: a GeoPackage; by default the first detection layer&apos;s GeoPackage, else `&lt;project&gt;_review.gpkg` next to the project. The log is the table `birdseye_verdicts` (a point layer, added to the map as &quot;Review verdicts&quot;, showing each unit&apos;s current verdict and the targets you added).
- **Reviewer**: your name, recorded with every verdict (default: your login name).
- **Review units**: *Consensus clusters* (the default, as described above: one unit per spot, best when several layers are reviewed) or *the method&apos;s* units, built as the method builds them: every detection within EPS_PRED of an in-view geotag is set aside on its own; per frame, the detections that stay are grouped by complete linkage on their pixel positions at 30 px (every two detections of a group at most 30 px apart). Each group is one unit seen in one frame, so a spot is judged once per frame that saw it (propagation, when on, carries a verdict to the same spot in the other frames); its key ends with `@&lt;frame id&gt;`. The scores are computed the same way with either: each cluster of a layer resolves once over all the judgements of the units near it.
- **Clustering and matching** (the method&apos;s values, but for the points count): grid cell 3 cm, EPS 0.20 m, minimum points 2, *points count* detections (the minimum points count the detections within EPS; *Cells (the method&apos;s)* counts each occupied grid cell once, as Cluster detections explains — a spot whose detections all fall in one cell then never becomes a unit), EPS_PRED 0.20 m (a unit is *matched* when a geotag in view lies within EPS_PRED of its core points), edge buffer 0 px; chip window (px of the image around the detection); map scale.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/review.md" line="13"/>
        <source>## Reviewing</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/review.md" line="15"/>
        <source>Units with no geotag nearby come first (they need you), then the others, most-seen first. For the current unit the dock shows up to four frames that detected it (highest score first): a window around the detection, each layer&apos;s detection as a ring (one colour per layer), geotags as red crosses with an open centre; the map is centred on the unit with the survey points visible.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/review.md" line="17"/>
        <source>**Detections found on a raster** are reviewed the same way, one raster at a time (frame and raster detections are not reviewed together): each unit shows one chip, a window of the raster around the detection (the raster the layer records, so keep it where it was); the geotags in view are those on the raster&apos;s valid pixels, and one detection can be a unit, as in Cluster and Evaluate detections. The chip window is then in the raster&apos;s pixels.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/review.md" line="19"/>
        <source>Keys (click the review area first): **1** or **C** confirmed real · **2** or **H** hard negative · **3** or **U** uncertain · **0** or **Backspace** unreviewed (withdraws your verdict) · **N** or **→** next · **P** or **←** previous · **Home** / **End** first / last · **Ctrl+Z** undo · **A** add a missed target (click the map; Esc cancels). After a verdict the dock moves to the next unit (untick &quot;Next unit after a verdict&quot; to stay). Filters show the units one layer fired at, or by verdict (to review, each verdict, propagated only, conflicting, no geotag nearby, added targets).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/review.md" line="21"/>
        <source>**Propagation** (off by default): when on, a verdict also votes on the units chained to this one by gaps of at most 0.20 m (DBSCAN over the unit positions), with provenance `propagated:dbscan_0.20m/&lt;unit&gt;`. Every source keeps its own vote; where votes disagree the unit is resolved under three conventions — positive-wins, majority-wins (a tie between confirmed real and hard negative is uncertain), hard-negative-wins — all kept and shown side by side. **Uncertain and unreviewed are abstentions, not votes**: confirmed real + uncertain resolves to confirmed real under every convention; only uncertain judgements leave a unit uncertain.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/review.md" line="23"/>
        <source>**Scores**: per detection layer, recall and GMCF before review and after it under each convention, computed by the same code as Evaluate detections from this log (running Evaluate detections with the log as REVIEW gives the same numbers). GMCF is a lower bound on precision, not precision. Recall after review is printed &quot;≥ x&quot; only when no added target counts (a = 0); with added targets (in view, where no cluster fired and no geotag lies within EPS_PRED) it is a point value under the assumptions Evaluate detections states in its help.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/review.md" line="25"/>
        <source>**Nothing is lost**: every verdict is committed to the GeoPackage in its own transaction before the dock moves on; the log is append-only (undo appends rows restoring the previous verdicts; the table refuses edits and deletions). Each row records the unit, verdict, provenance, reviewer, UTC time, position, the layers that fired, the clustering and matching parameters and a SHA-256 digest of each input layer. Reopening the project, or the dock with the same layers, resumes at the unit and filters where you stopped. If an input layer changed since verdicts were recorded (its digest differs), or the parameters did, a warning says so. A review saved before the points count was recorded was built counting cells, and reopens that way.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>help:screencheckpoints</name>
    <message>
        <location filename="../resources/help/screencheckpoints.md" line="1"/>
        <source>Runs several ONNX checkpoints over several validation flights at one threshold and reports, per checkpoint, the figures the method tabulates — pooled recall, pooled GMCF, their F1, detections per frame and the relative review load — next to health guards that tell which checkpoints are healthy, and which of those lie on the frontier of recall against GMCF. A screen before a full sweep. Give held-out flights too and it reports how each checkpoint&apos;s figures carry over to them (the transfer report, below).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/screencheckpoints.md" line="3"/>
        <source>## Presets</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/screencheckpoints.md" line="5"/>
        <source>- **Method** (default): every flight is cut into **blocks of 500 frames** and the threshold is **0.03**, as the method screens.
- **BirdsEye**: each flight is one block, and each checkpoint runs at its own default threshold (from its metadata).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/screencheckpoints.md" line="8"/>
        <source>The two fields below the preset override it when filled: **Detection threshold** (a probability) and **Frames per block** (0 = each flight whole).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/screencheckpoints.md" line="10"/>
        <source>A block is a run of consecutive frames of one flight, in the frame layer&apos;s order (the importers write frames in time order); the last block of a flight holds what is left (1,234 frames in blocks of 500: 500, 500 and 234). Each block is scored as a flight is: its own in-view geotags (in view of the block&apos;s frames) and its own clusters; a geotag seen in two blocks counts in both.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/screencheckpoints.md" line="12"/>
        <source>## Per checkpoint</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/screencheckpoints.md" line="14"/>
        <source>Pooled by micro-averaging over every block of every flight: counts summed, one division.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/screencheckpoints.md" line="16"/>
        <source>- **recall_pre** and **gmcf_pre** exactly as in Evaluate detections (clusters of DEDUP_CM, EPS_M, MIN_SAMPLES; matches within EPS_PRED_M of core points; geotags in view by EDGE_BUFFER_PX).
- **f1_geo** = 2 · recall_pre · gmcf_pre / (recall_pre + gmcf_pre), the harmonic mean of pooled recall and pooled GMCF — the F1 every table of the method prints (e.g. recall 0.8 and GMCF 0.6 give 0.686). It is 0 when both are 0 and empty when either is undefined.
- **detections_per_frame**: all detections / all processed frames.
- **review_load** = detections per frame / the detections per frame of the lightest healthy checkpoint (1.0 = the lightest review; an unhealthy checkpoint gets its ratio to that same reference). Empty when no checkpoint is healthy.
- **f1_pixel**, the pixel-space F1 under its own name, for choosing checkpoints only — never a field score: in every frame, detections are matched one-to-one, nearest first, to the labels Write labels would draw (the in-view geotags projected into that frame) within **f1_pixel_radius_px** = PIXEL_RADIUS_PX (default 10 px); TP, FP, FN are summed over frames, blocks and flights, F1 = 2TP / (2TP + FP + FN).
- **Health guards**: *collapsed* when the distinct-position fraction (distinct detection pixels, rounded to whole pixels, / detections, over everything) is below COLLAPSED_BELOW (default 0.05): a collapsed model fires at the same pixels in every frame. *Too sparse* when the detections per processed frame of its worst block (**worst_block**) fall below SPARSE_BELOW (default 1.7). Unhealthy checkpoints are listed but never on the frontier nor the review-load reference.
- **Frontier**: healthy checkpoints that no other healthy one beats on both recall_pre and gmcf_pre.
- Also: unmatched clusters (clusters − hit clusters), pixel TP/FP/FN, the pooled counts, and the threshold each checkpoint ran at.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/screencheckpoints.md" line="25"/>
        <source>## Survey density</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/screencheckpoints.md" line="27"/>
        <source>Per flight and pooled: the in-view geotags per processed frame — for every frame, how many geotags are in view of it — as mean, median, 10th and 90th percentiles, minimum–maximum and the share of frames that see none. A cluster is a hit only where the survey put a geotag, so a sparsely surveyed site has more unmatched clusters and a lower GMCF for the same detector: compare GMCF across sites only with their densities.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/screencheckpoints.md" line="29"/>
        <source>## Validation → held-out (the transfer report)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/screencheckpoints.md" line="31"/>
        <source>With **held-out flights** (HELDOUT_FRAMES), every checkpoint is also run on them, screened exactly as on the validation flights (same preset, threshold, blocks and clustering), and reported side by side:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/screencheckpoints.md" line="33"/>
        <source>- per checkpoint: recall and GMCF on the validation flights and on the held-out flights, and their changes **ΔRecall** and **ΔGMCF** = held-out − validation (empty where either figure is undefined);
- across checkpoints: **Spearman&apos;s rank correlation ρ** between the validation and the held-out figure, for recall and for GMCF, over the checkpoints healthy on the validation flights (the ones you would choose from); tied figures share their average rank. Near 1: the validation ranking holds on the held-out flights; near 0 or below: the checkpoint that looked best on validation need not be best there. Fewer than 3 such checkpoints give no ρ but a note saying &quot;not enough checkpoints&quot; (with 2, ρ is ±1 whatever the figures); so does a figure that is the same for every checkpoint (&quot;no ranking&quot;).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/screencheckpoints.md" line="36"/>
        <source>GMCF moves with how densely each site was surveyed (its survey density), so a GMCF that changes between sites, or a GMCF ranking that does not hold, says as much about the surveys as about the checkpoints; recall, taken over the surveyed targets only, is the figure to compare across sites.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/screencheckpoints.md" line="38"/>
        <source>## Parameters</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/screencheckpoints.md" line="40"/>
        <source>- **ONNX checkpoints**: model files with BirdsEye metadata (see Detect targets).
- **Validation flights**: frame layers whose `image` field points at the frames&apos; images; every frame is processed.
- **Geotags**: any point layer.
- **Held-out flights** (HELDOUT_FRAMES, optional): frame layers with their images, as the validation flights; each is scored on its own, never pooled with the validation flights.
- **Held-out geotags** (HELDOUT_GEOTAGS, optional): the survey of the held-out site; empty: the Geotags above.
- **Preset**, **Detection threshold**, **Frames per block**: as above.
- **DEDUP_CM, EPS_M, MIN_SAMPLES, CORE_COUNT, EPS_PRED_M, EDGE_BUFFER_PX**: as in Evaluate detections (defaults 3 cm, 0.20 m, 2, detections, 0.20 m, 0 px; CORE_COUNT *cells* counts as the method does); EDGE_BUFFER_PX also drops detections that close to the image border, as Detect does.
- **Terrain model (DEM)**, **DEM heights are measured from**, **geoid undulation N (m)**, **Ground model without a DEM** (GROUND_MODEL, advanced): as in Detect targets; the checkpoints&apos; detections, the in-view test and the pixel labels all stand on this ground (with a DEM, frames without an altimeter ground are placed too).
- **PIXEL_RADIUS_PX** (px), **COLLAPSED_BELOW**, **SPARSE_BELOW** (detections per frame): as above.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/screencheckpoints.md" line="50"/>
        <source>## Outputs</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/screencheckpoints.md" line="52"/>
        <source>- **Checkpoint table (CSV)** and **JSON**: one row per checkpoint with the figures above (with held-out flights also recall_pre_heldout, gmcf_pre_heldout, delta_recall, delta_gmcf); the JSON adds the operating point, the preset, the block size, the block labels and `survey_density`, and with held-out flights a `heldout` block (its flights, blocks, survey density and checkpoint rows) and a `transfer` block (per checkpoint the figures on both sides and their changes; `spearman` with ρ, the number of checkpoints and a note for recall and GMCF).
- **Frontier plot (PNG)**: gmcf_pre against recall_pre per checkpoint (validation flights).
- **Report (HTML)**: the checkpoint tables, survey densities and, with held-out flights, the transfer table and the rank correlations.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>help:sealpreregistration</name>
    <message>
        <location filename="../resources/help/sealpreregistration.md" line="1"/>
        <source>Fixes, before a held-out flight is scored, what will be judged: a selection rule whose arms are checkpoints (identified by the SHA-256 digest of the ONNX file), **each with its own full operating point**, plus — for the record only — the configurations you looked at while choosing. The rule is written as canonical JSON and sealed with SHA-256 over the rule, the model digests and the sealing time (UTC).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/sealpreregistration.md" line="3"/>
        <source>Evaluate detections verifies the seal before scoring with the rule and refuses a rule whose content was changed after sealing, or detections from a model the rule does not name. When several arms share one checkpoint (the method&apos;s arms often do, at different operating points), the arm to score must be named.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/sealpreregistration.md" line="5"/>
        <source>A seal is a fingerprint, not a signature: anyone can re-seal an edited rule. It proves the rule unchanged only against a copy of the seal kept where you cannot edit it later — e-mail it to a colleague, write it in the lab notebook or commit it. The log prints it.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/sealpreregistration.md" line="7"/>
        <source>## Where the arms come from (one of three)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/sealpreregistration.md" line="9"/>
        <source>- **Arms file**: the output of Select arms — the method&apos;s three arms (max_f1, max_recall, lowest_review_burden), each sealed with the operating point the sweep chose for it. With ONNX checkpoints given too, every arm&apos;s digest must be one of theirs (the seal then names files you have); without them, the digests the sweep recorded are sealed.
- **Arms typed in** (ARM_LINES), one per line: `name: checkpoint file, threshold, eps_m, min_samples, eps_pred_m`, e.g. `max_f1: model_b.onnx, 0.05, 0.20, 2, 0.20` (threshold a probability, eps_m and eps_pred_m in metres, min_samples a whole number). The checkpoint is named by its file name among the ONNX checkpoints; DEDUP_CM, CORE_COUNT and EDGE_BUFFER_PX below apply to every arm. Blank lines and lines starting with `#` are skipped.
- Neither: one arm per ONNX checkpoint, all at the **Detection threshold** and the clustering parameters below.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/sealpreregistration.md" line="13"/>
        <source>Arm names must be distinct.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/sealpreregistration.md" line="15"/>
        <source>## Parameters</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/sealpreregistration.md" line="17"/>
        <source>- **ONNX checkpoints**: each file&apos;s SHA-256 digest is computed; required unless an arms file is given. Two checkpoints may not share a file name.
- **Arms file**, **Arms typed in**: as above (not both).
- **Detection threshold** (probability, default 0.5) and **DEDUP_CM, EPS_M, MIN_SAMPLES, CORE_COUNT, EPS_PRED_M, EDGE_BUFFER_PX** (defaults 3 cm, 0.20 m, 2, detections, 0.20 m, 0 px; see Cluster detections for their meaning): the operating point of every arm when neither an arms file nor typed arms are given; with typed arms, DEDUP_CM, CORE_COUNT and EDGE_BUFFER_PX only. Every sealed operating point records its core_count; arms from an arms file keep theirs (cells for arms chosen from a sweep made before it was recorded).
- **Descriptive configurations** (optional): a JSON from Sweep operating points (its Pareto configurations are recorded) or Screen checkpoints (its checkpoint table), or any JSON list. Recorded, never used to decide.
- **Note**: free text — what was chosen on which flights, and what will be scored.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/sealpreregistration.md" line="23"/>
        <source>## Output</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/sealpreregistration.md" line="25"/>
        <source>- **Sealed rule (JSON)**: `schema`, `rule` (arms — each with name, checkpoint, model_digest and operating_point —, descriptive, note), `model_digests`, `sealed_at`, `seal`. The seal is the SHA-256 of the canonical JSON (sorted keys, no spaces, UTF-8) of everything but the seal itself.
- **Seal**: the hex digest, also printed in the log.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>help:selectarms</name>
    <message>
        <location filename="../resources/help/selectarms.md" line="1"/>
        <source>Applies the method&apos;s three selection rules to a sweep and writes the three **arms** — each a checkpoint with its full operating point — that Seal a preregistered selection rule then seals.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/selectarms.md" line="3"/>
        <source>Every rule looks only at the sweep&apos;s **credible configurations on its Pareto front** (recall_pre against gmcf_pre over every checkpoint&apos;s configurations; see Sweep operating points for the credibility filter):</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/selectarms.md" line="5"/>
        <source>- **max_f1**: the highest **f1_geo** = 2 · recall_pre · gmcf_pre / (recall_pre + gmcf_pre), the harmonic mean of pooled recall and pooled GMCF. Ties: the higher recall, then the earlier row of the table.
- **max_recall**: the highest **recall_pre**. Ties: the higher gmcf_pre, then the earlier row.
- **lowest_review_burden**: the fewest **detections per frame** — what a reviewer walks through, frame by frame, and what Screen checkpoints&apos; review load divides. Configurations that differ only in EPS_M, MIN_SAMPLES or EPS_PRED_M have the same detections per frame; among them: the higher f1_geo, then the higher recall, then the earlier row.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/selectarms.md" line="9"/>
        <source>The rules may pick the same checkpoint, or even the same configuration, for more than one arm; each arm keeps its own name.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/selectarms.md" line="11"/>
        <source>## Parameters</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/selectarms.md" line="13"/>
        <source>- **Sweep**: the JSON output of Sweep operating points.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/selectarms.md" line="15"/>
        <source>## Output</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/selectarms.md" line="17"/>
        <source>- **Arms (JSON)**: `schema` (`birdseye-arms/1`), `sweep` (the file, flights, grid and credibility limits the arms were chosen from) and `arms`: per arm its `name`, the `rule`, `checkpoint`, `model_digest` (SHA-256 of the ONNX file), the full `operating_point` (threshold, dedup_cm, eps_m, min_samples, eps_pred_m, edge_buffer_px, core_count — cells when the sweep recorded none, as sweeps before it was recorded counted), its `scores` in the sweep (recall_pre, gmcf_pre, f1_geo, detections_per_frame and the counts) and `sweep_row` (its row in the sweep&apos;s table, from 1). The log prints the three arms.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>help:sensorbound</name>
    <message>
        <location filename="../resources/help/sensorbound.md" line="1"/>
        <source>Answers, before you buy an INS or an altimeter: does this pose-noise budget keep every projected label inside the soft-label radius? For a nadir camera over level ground it computes, at each altitude, the label covariance Σ_u (px²) that the pose noise causes at every pixel of the frame, and checks it against the tolerance in two ways. The **trace bound** (sup tr Σ_u ≤ λ_target) is simple and sufficient but pessimistic; the **exact bound** (sup λ_max(Σ_u) ≤ λ_target) is necessary and sufficient. λ_target = (r/3)² px² for a label radius r drawn at 3σ. Lens distortion is ignored.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/sensorbound.md" line="3"/>
        <source>For each altitude you get both suprema, **κ*** = λ_target / sup (the largest factor by which every variance of your budget may grow; accept when κ* ≥ 1), the verdicts, the worst pixel, each axis&apos;s share of the error, and two **balanced budgets**: the sigmas that use the whole tolerance with no axis starved, under the trace bound and under the exact bound.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/sensorbound.md" line="5"/>
        <source>## Platform preset</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/sensorbound.md" line="7"/>
        <source>- **Platform preset**: *Custom* (default) uses the values below. A preset sets the camera, the pose sigmas and the camera mount together (the typed ones are then ignored; a calibration file still overrides the camera):
  - *Deployed platform (BirdsEye method)* — the payload&apos;s calibrated camera (1920 × 1200 px) and its RTK INS + radar altimeter budget `0.01,0.01,0.06,0.04,0.04,0.13`, on the method&apos;s camera mount.
  - *DJI RTK drone, poses from its image metadata* — what **Import drone images** places frames with, before photogrammetric refinement. Camera: the Mavic 3 Enterprise wide camera, 5280 × 3956 px, 84° diagonal field of view (DJI&apos;s specifications), so fx = fy = (diagonal / 2) / tan 42° = 3663.69 px, principal point at the centre. Position: RTK fix 1 cm + 1 ppm horizontal and 1.5 cm + 1 ppm vertical — the accuracy DJI states for the Mavic 3 Enterprise RTK module, the Matrice 300/350 RTK and the Phantom 4 RTK (dji.com specifications) — at a 1 km baseline: x, y 0.011 m, z 0.016 m. Attitude: DJI states the gimbal&apos;s angular vibration (±0.01° or better, e.g. the Zenmuse H20 series) but **not** the accuracy of the attitude written into the image, which is the aircraft&apos;s IMU and compass estimate the gimbal stabilises against. The preset uses what we measured on a real DJI RTK flight against photogrammetry-refined poses — the camera tilted 0.4–0.9° where the metadata said 0.1°, the heading off by up to 1.8° — as 1σ: roll 0.5°, pitch 0.5°, yaw 1.0°. Sigmas: `0.011,0.011,0.016,0.5,0.5,1`. Mount: nadir, image top towards the nose (roll and pitch share one sigma, so the method&apos;s mount gives the same figures).

  With the default tolerance (r = 30 px, σ_label = 10 px) the DJI preset is **rejected at 10 m** (exact κ* ≈ 0.02; at 20 m too): at a frame corner one σ of heading moves a label by about 58 px, of roll or pitch by 43–51 px, while the RTK position moves it by 4–5 px. The attitude carries over 95 % of the error, the heading most; the position alone would pass. Metadata poses are good for footprints and flight planning, not for pixel-accurate labels — refine the poses by photogrammetry (**Refine frame poses**) first. Heights are a second risk the budget does not show: the depth comes from `RelativeAltitude`, a fused height for which DJI states only a hovering accuracy (±0.1 m with RTK), and on the real flight the heights read 1.45 m low.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/sensorbound.md" line="13"/>
        <source>## Camera</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/sensorbound.md" line="15"/>
        <source>- **Camera calibration**: a Kalibr camchain YAML or an OpenCV YAML. When given it **overrides** the typed intrinsics below (only fx, fy, cx, cy and the image size are used).
- **fx, fy** [px]: focal lengths. **cx, cy** [px]: principal point (pixel (0, 0) is the centre of the top-left pixel). **Image width, height** [px]. The defaults are the camera of the platform the BirdsEye method was deployed on (1920 × 1200 px).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/sensorbound.md" line="18"/>
        <source>## Budget and tolerance</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/sensorbound.md" line="20"/>
        <source>- **Altitudes** [m]: heights above the ground, comma-separated, e.g. `10,20`. Each must be greater than 0.
- **Pose sigmas** (1σ), comma-separated, in this order: `x, y, z` in **metres**, `roll, pitch, yaw` in **degrees**. x and y are the horizontal position errors (image right and image down), z the vertical one (along the optical axis); roll, pitch and yaw are attitude errors, turned into camera rotations by the camera mount. Default: the deployed platform, `0.01,0.01,0.06,0.04,0.04,0.13`.
- **Camera mount**: how roll, pitch and yaw turn the camera.
  - *As the method* (default): roll turns the camera about its x axis (image right), pitch about its y axis (image down), yaw about the optical axis — the method applies the attitude sigmas directly to the camera-frame rotation vector. This is also what a nadir camera mounted with the image&apos;s right edge towards the nose sees. With it the deployed platform gives the method&apos;s table: at 10 m and r = 30 px the balanced exact budget is x 13.64 mm, y 13.45 mm, z 49.12 mm, roll 0.0753°, pitch 0.0741°, yaw 0.3013°, and the deployed budget&apos;s shares are 16.7 / 16.7 / 42.9 / 8.5 / 9.0 / 6.1 % (x, y, z, roll, pitch, yaw) — where the method evaluated u = 0…W, v = 0…H, one pixel beyond the last pixel centre. On the frame&apos;s own pixels (u = 0…W − 1, v = 0…H − 1), which BirdsEye evaluates, z is 49.19 mm, yaw 0.3016° and the shares 16.8 / 16.8 / 42.8 / 8.5 / 9.0 / 6.1 %.
  - *Nadir camera, image top towards the nose*: roll and pitch are the attitude errors of a forward-right-down body. Roll (about the flight direction) moves labels across the image (along u), pitch (about the wings) along the image (along v), yaw turns them about the principal point. Against the method&apos;s mount, roll and pitch trade places: the budget above becomes roll 0.0741°, pitch 0.0753° and the shares 9.0 / 8.5 %. When σ_roll = σ_pitch both mounts give the same numbers.
- **Label tolerance r** [px]: the label radius at 3σ; default 30 px (σ_label = r/3 = 10 px).
- **Grid stride** [px]: the bound is evaluated on the pixel centres u = 0, stride, …, W − 1 and v = 0, stride, …, H − 1, the last pixel always included. 1 = every pixel (W × H points; about 0.3 s per altitude for 1920 × 1200); larger strides are faster and almost always give the same verdicts, because the worst pixel is a corner.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/sensorbound.md" line="28"/>
        <source>## Outputs</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/sensorbound.md" line="30"/>
        <source>- **Results (JSON)**: `{&quot;altitudes&quot;: [{altitude_m, sup_trace_px2, sup_lmax_px2, kappa_trace, kappa_exact, verdict_trace, verdict_exact, worst_pixel, balanced_trace_sigma, balanced_exact_sigma, budget_share, …}], &quot;inputs&quot;: {…, &quot;mount&quot;, &quot;axis_convention&quot;}}` (`mount`: `method` or `nadir_top_forward`). Suprema in px², worst pixel as [u, v] px, sigma lists in the units of Pose sigmas (m, m, m, °, °, °), budget shares as fractions summing to 1. κ* is null for an all-zero budget (unbounded).
- **Report (HTML)**: verdict table, the budgets per altitude and a plot of the λ_max field with the tolerance contour, all in one file you can mail.
- **λ_max field (GeoTIFF)**, optional: one Float32 band per altitude (in the order given), λ_max in px² at every grid point. The raster is in **pixel coordinates without a CRS** (x = u + 0.5, y = −(v + 0.5)): it lies exactly over a frame opened in QGIS without georeferencing, not on the map. When the stride&apos;s grid does not reach the last pixel the raster stops at the last multiple of the stride.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/sensorbound.md" line="34"/>
        <source>The summary of each altitude is printed in the log. The same numbers appear live in the **Sensor-bound calculator** panel (BirdsEye menu).</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>help:simulatecampaign</name>
    <message>
        <location filename="../resources/help/simulatecampaign.md" line="1"/>
        <source>Makes a complete synthetic survey campaign — rover geotags, drone pose log, frames and camera calibration — in exactly the formats BirdsEye imports, together with the ground truth behind it. Use it to try the whole workflow without a field trip, to test a setting before flying, or to train and evaluate a detector on targets whose true positions are known. The same SEED always gives the same files.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/simulatecampaign.md" line="3"/>
        <source>What is simulated: a field (soil with clods, cracks, stones, straw, specks and crop rows of seedlings, under sun and moving cloud shadows) with burrow-like targets — a dark hole 3–8 cm across with a lighter crescent of loose soil — and look-alikes that are **not** targets (dark moist patches, shaded depressions, loose-soil mounds without a hole, stones with their shadows, dung). An RTK rover surveys the targets (a few are missed, a few presses hit nothing). A multirotor flies lawnmower lines over the field carrying an RTK INS, a radar altimeter and the nadir camera; each frame is rendered through the true pose and the lens distortion, with exposure drift, vignetting, blur, sensor noise and JPEG compression. The field lies on level ground or on terrain — a uniform slope, or a slope with smooth hills — so you can see what slopes do to labels placed on a level plane, and check labels made with the terrain model (DEM) the campaign writes.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/simulatecampaign.md" line="5"/>
        <source>## Parameters</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/simulatecampaign.md" line="7"/>
        <source>- **SEED** — random seed (integer). Same seed and parameters → identical files.
- **N_TARGETS** — number of targets (burrows) in the field (default 40).
- **FIELD_WIDTH_M**, **FIELD_LENGTH_M** — size of the surveyed field in metres, east–west and north–south (default 40 × 30 m), centred on the site.
- **ALTITUDE_M** — flying height of the drone above the ground in metres (default 10; 2.3 mm/px with the default camera).
- **SPEED_MS** — flight speed on the survey lines in m/s (default 2.5; the drone slows in the turns).
- **SIGMAS** — pose-sensor noise Σ0 of the INS as six standard deviations: x, y, z in metres (east, north, up), roll, pitch, yaw in degrees (small rotations about the body axes), independent for every logged message. Default: the deployed platform `0.01,0.01,0.06,0.04,0.04,0.13`. `0,0,0,0,0,0` logs the true poses.
- **NOISE_OFF** — turns off every measurement error at once: Σ0, altimeter noise and low-SNR bursts, RTK-float episodes, rover RTK noise and float fixes. The frames are unchanged.
- **PLATFORM** — what flies: the *RTK INS payload* (default; the pose log, radar altimeter and calibrated camera described here) or a *DJI drone*, which records no pose log and writes each frame&apos;s pose into the JPEG itself (see **A DJI drone** below).
- **RENDER** — write the frames and the orthomosaic (default on). Off: poses, geotags, calibration and truth only (seconds instead of minutes).
- **TERRAIN** — the ground the field lies on: *Flat* (default; level ground at GROUND_HEIGHT_M), *Plane* (a uniform slope of SLOPE_DEG through the site centre, at GROUND_HEIGHT_M there) or *Hills* (that slope plus smooth random hills of RELIEF_M, drawn from the SEED). Over terrain the drone **follows the terrain**: it keeps ALTITUDE_M above the ground directly beneath it (as a terrain-following mode does), climbing and descending with it; the altimeter ranges to the terrain along the body&apos;s down axis, targets and geotags lie on the terrain, and every frame is rendered over it. The terrain is written as `truth/dem.tif` — give it to the algorithms that take a DEM (*Import a flight log*, *Write labels*) with its heights measured from the ellipsoid.
- **SLOPE_DEG** — slope of the terrain in degrees from level (0–45; default 0; plane and hills). The level-plane label model is good to about 10°.
- **SLOPE_ASPECT_DEG** — the direction the slope faces, i.e. downhill, in degrees clockwise from true north (0 = the ground falls towards the north; default 0).
- **RELIEF_M** — height of the hills from the lowest valley to the highest top over the terrain model, in metres (default 0; hills only).
- **SITE_LAT**, **SITE_LON** — site centre in WGS84 degrees (default a farm near Toowoomba, −27.55, 151.95).
- **GROUND_HEIGHT_M** — ellipsoidal (WGS84) height of the field in metres (default 400); over terrain, the height at the site centre.
- **FPS** — camera frame rate in frames per second (default 5).
- **INS_RATE_HZ** — INS message rate in Hz (default 50); every message is a row of the pose log.
- **IMAGE_WIDTH**, **IMAGE_HEIGHT** — frame size in pixels (default 1920 × 1200, the deployed camera: fx 4264.49, fy 4262.89, cx 958.46, cy 592.50 px, radtan distortion k1 −0.08, k2 0.12, p1 0.0004, p2 −0.0003). Other sizes scale the focal lengths and principal point, keeping the field of view.
- **SIDE_OVERLAP** — overlap of neighbouring lines&apos; footprints as a fraction; empty (the default): 0.3 for the payload, 0.7 for a DJI drone.
- **RADALT_SIGMA_M** — radar altimeter noise in metres (default 0.03).
- **RTK_SIGMA_M** — rover RTK noise of the geotags in metres, horizontal per axis (vertical twice that; default 0.015).
- **N_MISSED** — targets left out of the survey (default 2). **N_SPURIOUS** — geotags with no target (default 2).
- **RTK_FLOAT_EPISODES** — short spells (2–5 s) of RTK float in the pose log, with extra position error (default 1).
- **ORTHO_PIXEL_M** — ground size of a pixel of the orthomosaic, in metres (default 0.02, i.e. 2 cm; 0.005–1). Burrows 3–8 cm across are dark spots of a few pixels at 2 cm; at 1 cm they show their crescent of loose soil. Maps that would exceed 64 million pixels (a 25 ha field at 2 cm) get a pixel doubled until they fit.
- **LOOK_ALIKE_DENSITY** — how many target-sized look-alikes (dark moist patches, shaded depressions, loose-soil mounds, stones) the field holds, as a multiple of the default density (default 1; 0–20; none closer than 0.35 m to a target&apos;s edge). Raise it to make a detector&apos;s false alarms, and the review&apos;s hard negatives, common.
- **HILL_WAVELENGTH_M** — typical distance from one hill to the next, in metres (default 40; hills only).
- **FORWARD_OVERLAP** — DJI drone only: overlap of consecutive photos along a line as a fraction (default 0.8); the drone takes a photo every (1 − FORWARD_OVERLAP) footprint lengths at SPEED_MS, as a mapping mission does (FPS is not used).
- **DJI_DEWARPED** — DJI drone only: the drone removes the lens distortion itself and says so (`DewarpFlag` 1); the frames are rendered without distortion (default off: the JPEGs carry the lens distortion, `DewarpFlag` 0).
- **GEOID_UNDULATION_M** — geoid height N in metres for the rovers&apos; `altMSL = altWGS84 − N`; empty: EGM96 at the site.
- **OUTPUT_FOLDER** — where the campaign is written. Frames (timestamped, or `DJI_nnnn.JPG`) and the `images.csv` of an earlier run into the same folder are removed first; other files are left alone. The frames&apos; folder is returned as **FRAMES_FOLDER** (give it to *Import drone images* as IMAGES).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/simulatecampaign.md" line="38"/>
        <source>## A DJI drone (PLATFORM = DJI drone)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/simulatecampaign.md" line="40"/>
        <source>A consumer drone flying a mapping mission: photos only on the survey lines, spaced for FORWARD_OVERLAP, lines spaced for SIDE_OVERLAP (80 % and 70 % by default — the overlap photogrammetry needs; the simulated soil gives SIFT features enough to match neighbouring photos), from a gimbal that holds the camera looking straight down. The camera is of the size of a Mavic 3 Enterprise&apos;s wide camera (4/3 sensor 5280 × 3956 px, 24 mm equivalent, 84° diagonal field of view) scaled to IMAGE_WIDTH (and cropped to IMAGE_HEIGHT&apos;s aspect ratio), with a lens distortion of the size DJI&apos;s `DewarpData` shows; the values are the simulator&apos;s, not a calibration. At 1920 × 1200 px from 10 m a pixel is 7.5 mm on the ground. Photogrammetry needs fine pixels on this soil: at 9 mm per pixel SIFT matches hundreds of points between neighbouring photos, at 15 mm only a few dozen — fly lower or render larger images.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/simulatecampaign.md" line="42"/>
        <source>Each frame is `frames/DJI_0001.JPG`, … with the EXIF and XMP metadata **Import drone images** reads: EXIF make `DJI`, model `M3E`, serial number, image size, 35 mm equivalent focal length (24 mm), `DateTimeOriginal` with sub-seconds (UTC) and GPS latitude, longitude and altitude; XMP `drone-dji:` `GpsLatitude`, `GpsLongitude`, `AbsoluteAltitude` (above mean sea level, using N), `RelativeAltitude` (above the take-off point, the site centre at GROUND_HEIGHT_M), `GimbalRoll/Pitch/YawDegree`, `FlightRoll/Pitch/YawDegree`, `RtkFlag` 50 (fixed), `RtkStdLon/Lat/Hgt`, `CalibratedFocalLength`, `CalibratedOpticalCenterX/Y`, `DewarpData` and `DewarpFlag`, `CameraSerialNumber`. No pose log, image list or calibration file is written (an earlier run&apos;s are removed).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/simulatecampaign.md" line="44"/>
        <source>The pixels are rendered through the **true** pose; the metadata says what the drone believes, with the errors measured on a real RTK flight. The drone&apos;s attitude belief is the truth turned by a small error rotation, which the gimbal — stabilised against that belief — and the aircraft attitude share:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/simulatecampaign.md" line="46"/>
        <source>- heading: a bias of 1–2° (magnitude drawn from the SEED, either sign) plus a slow drift (σ 0.2°, over about a minute);
- tilt: the camera is truly tilted by a bias of 0.5–1° in a direction fixed in the aircraft body (an accelerometer bias turns with the aircraft), plus a slow drift (σ 0.1°, over about 20 s), while the metadata says it looks straight down;
- heights: `AbsoluteAltitude`, EXIF altitude and `RelativeAltitude` all read 1.5 m low (σ 1.5 cm about that), so the depth the importer uses is 1.5 m short;
- position: an RTK fix&apos;s noise, σ 1 cm horizontally; gimbal angles jitter by 0.01°.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/simulatecampaign.md" line="51"/>
        <source>Labels made from this metadata miss the targets by tens of pixels (at 8 m with 1280 × 960 px frames: median 65–80 px, 95 % about 100–120 px, mostly the 1.5 m height error); refining the poses by photogrammetry (**Refine frame poses**) brings them back to about a pixel. NOISE_OFF makes the metadata exact (to the 0.01° and 1 mm it is written with): labels from it sit on the rendered targets. The errors drawn are in `truth/campaign.json` (`dji`) and per frame in `truth/dji_metadata_errors.csv` (`frame_index, image, heading_error_deg, tilt_error_deg, height_error_m, horizontal_error_m`: metadata − truth); `truth/frames_true.csv` then holds the true *gimbal* poses (quaternion gimbal → NED: x the optical axis, y image right, z image down), with `pose_row` and `radalt_m` empty.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/simulatecampaign.md" line="53"/>
        <source>## Files written in OUTPUT_FOLDER</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/simulatecampaign.md" line="55"/>
        <source>- `geotags.csv` — BirdsEye rover CSV, no header: `lat, lon, altWGS84, altMSL, gpsStatus, label` (degrees, metres; gpsStatus 4 = RTK fixed, 5 = float; label `burrow`), in the order the surveyor walked.
- `poses.csv` — BirdsEye pose log: `time_s, lat_deg, lon_deg, height_m, qw, qx, qy, qz, rtk_status, radalt_m, radalt_snr, strobe` (seconds, degrees, ellipsoidal metres, body forward-right-down → NED quaternion with yaw from true north, rtk_status 3 fixed / 2 float, altimeter range in metres along the body z axis and its SNR in dB — mostly above 13, with a few short low-SNR bursts of poor readings — and strobe = 1 on the rows of the camera&apos;s exposures).
- `images.csv` (`time_s, file`) and `frames/&lt;sec&gt;.&lt;nsec&gt;.jpg` — the frames, named by their timestamps (a few milliseconds after their strobe), JPEG quality 92.
- `calibration.yaml` — Kalibr camchain-imucam: intrinsics, radtan distortion, resolution, `T_cam_imu` (nadir camera, image up = forward, with a small lever arm and boresight) and `T_rad_imu` (the altimeter&apos;s lever arm).
- `field.geojson` — the field&apos;s boundary (the rectangle FIELD_WIDTH_M × FIELD_LENGTH_M the targets lie in, centred on the site), a WGS84 polygon: returned as **FIELD**, for *Partition field* and *Prepare field survey*.
- `truth/targets.csv` — every target: `id, lat, lon, h_ground, radius_m, contrast, surveyed, geotag_row, mound_radius_m, east_m, north_m` (geotag_row: its 1-based row in geotags.csv, empty if missed).
- `truth/distractors.csv` — the look-alikes: `id, kind, lat, lon, radius_m, east_m, north_m`.
- `truth/frames_true.csv` — every frame&apos;s true pose: `frame_index, image, pose_row, time_s, image_time_s, lat_deg, lon_deg, height_m, qw…qz, roll_deg, pitch_deg, yaw_deg, radalt_m, ground_h_m, line, speed_ms, exposure_gain` (radalt_m: the true altimeter range; ground_h_m: ellipsoidal height of the ground directly below the IMU).
- `truth/dem.tif` — over terrain only: the terrain the frames were rendered over, a GeoTIFF in the site&apos;s UTM zone with WGS84 ellipsoidal heights in metres (cells of 0.25 m, coarser for very large fields), covering the field, the flight and everything the frames see. Heights are interpolated bilinearly between cell centres. Also returned as the output **DEM**.
- `orthomosaic.tif` — the field seen straight down: a map of the simulated ground to draw the survey over, as a drone survey&apos;s orthomosaic is. An RGBA GeoTIFF (8 bits per band; alpha 0 outside the simulated ground) in the site&apos;s UTM zone, north up, with pixels of ORTHO_PIXEL_M on whole multiples of the pixel size (so the maps of neighbouring fields share one grid), compressed, with overviews. It is rendered from the same field model as the frames — not mosaicked from them — at each map pixel&apos;s centre, so every target lies exactly at its true position (a burrow&apos;s hole is within half a pixel of its geotag when NOISE_OFF is on) and there are no seams or relief displacement; the light is that of the flight&apos;s middle moment (cloud shadows included), the exposure that of the frames. Covers everything the frames see. Also returned as the output **ORTHOMOSAIC**; written only when RENDER is on (an earlier run&apos;s map is removed otherwise).
- `truth/campaign.json` — all parameters, the seed, site, local frame, output CRS (the UTM zone), geoid undulation, camera, flight plan, field style, terrain (kind, slope, aspect, relief, DEM cell size and extent), counts, the orthomosaic&apos;s grid (CRS, pixel size, extent) and package versions.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/simulatecampaign.md" line="67"/>
        <source>Rendering takes about half a second of one processor core per 1920 × 1200 frame, and each frame is about 1 MB; the default campaign has about 1,100 frames (roughly 10 minutes, 1.2 GB). Over terrain every pixel&apos;s ray is traced to the terrain model, which roughly doubles the rendering time. The orthomosaic adds about 5 seconds and 14 MB for the default field at 2 cm (5.5 million pixels). For a quick look use a smaller field, a lower FPS or smaller images. Progress is shown per frame and Cancel stops between frames.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>help:surveyreport</name>
    <message>
        <location filename="../resources/help/surveyreport.md" line="1"/>
        <source>What the field survey cost in people&apos;s time: geotags per worker-hour overall, per worker, per partition and per flight, from the capture time of every geotag. These are the figures the method reports for its field work (geotags per worker-hour; field time per flight), and the rate Partition field sizes the next field&apos;s pieces with.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/surveyreport.md" line="3"/>
        <source>**The rule.** A worker&apos;s captures, in time order, split into sessions wherever two are more than SESSION_GAP_MIN apart (a break, a walk back to the car). A session counts from its first to its last capture plus one typical interval (the worker&apos;s median time between captures within sessions), so a session of n captures counts n intervals and a single capture counts one. Worker-hours add up every worker&apos;s sessions: two people working 6 h each are 12 worker-hours, whatever the elapsed time. Geotags without a capture time are counted and left out of the rates.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/surveyreport.md" line="5"/>
        <source>## Parameters</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/surveyreport.md" line="7"/>
        <source>- **GEOTAGS** — the geotag point layer, with a `time_utc` field: ISO 8601 text (what Import geotags writes) or a date-and-time field (the field package&apos;s); a time without a zone is taken as UTC. A layer without the field, or without geotags, is refused.
- **WORKER_FIELD** — the field naming who took each geotag (default `worker`). A layer without it is one unnamed worker&apos;s.
- **SESSION_GAP_MIN** — a gap between two captures of one worker longer than this starts a new session [min] (default 20).
- **AREA** — the partitions, a polygon layer (optional; for example the output of Partition field). Each geotag belongs to the first partition holding it. **PARTITION_FIELD** names the partitions (empty: their row, 1.. in the layer&apos;s order).
- **FRAMES** — frame layers, one flight each (optional). A flight&apos;s geotags are those inside any of its footprints; its field time is the working time of their captures, by the same rule.
- **LABELS_SUMMARY** — the summary.json of a Write labels folder (optional): its labels and frames with labels are reported per worker-hour. **LABEL_COUNT** and **FRAME_COUNT** give the numbers directly and win over the file.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/surveyreport.md" line="14"/>
        <source>## Outputs</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/surveyreport.md" line="16"/>
        <source>- **Survey report (JSON)** — `overall` (geotags, geotags with a time, people, sessions, `worker_hours`, `geotags_per_worker_hour`, `elapsed_hours` from the first to the last capture of anyone, labels and frames per worker-hour), `workers` (each with its typical interval in seconds), `partitions`, `coverage` (partitions holding a geotag, geotags outside every partition) and `flights`.
- **Survey report (HTML)** — the same as short tables with units in the headers.
- **GEOTAGS_PER_WORKER_HOUR**, **WORKER_HOURS** [h], **PEOPLE**, **ELAPSED_HOURS** [h], **LABELS_PER_WORKER_HOUR**, **FRAMES_PER_WORKER_HOUR** — numbers for models and scripts (empty where there is nothing to divide).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/surveyreport.md" line="20"/>
        <source>For example, the method labelled 12,524 frames with 55,600 labels in about 12 worker-hours (two people for about 6 hours each): 55,600 / 12 = 4,633 labels and 1,044 frames per worker-hour. Read as 12 hours of elapsed time with both people at work, it would be 24 worker-hours and half those rates; the report counts worker-hours from the captures, so it never depends on such a reading.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>help:sweepoperatingpoints</name>
    <message>
        <location filename="../resources/help/sweepoperatingpoints.md" line="1"/>
        <source>Scores every checkpoint × detection threshold × EPS_M × MIN_SAMPLES × EPS_PRED_M combination on one or several flights — several checkpoints in, one table out — keeps the credible configurations and draws their Pareto front of recall against GMCF. Use it to choose operating points (Select arms applies the method&apos;s three rules to its output) before scoring a held-out flight.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/sweepoperatingpoints.md" line="3"/>
        <source>## Two ways in</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/sweepoperatingpoints.md" line="5"/>
        <source>- **ONNX checkpoints** + **frame layers** (one per flight, images in their `image` field): the sweep runs every checkpoint over every frame once and extracts the peaks at **every threshold of THRESHOLDS** from that frame&apos;s heatmap — exactly what Detect would find at each threshold, with one model run per frame instead of one per threshold.
- **Detection layers** made by Detect + **frame layers** (one per detection layer, same order; repeat a frame layer for each layer detected on it): each layer names its checkpoint (its `model` and `model_digest`) and is used **at the threshold it was detected at**. The threshold axis is then the set of thresholds the layers were detected at (THRESHOLDS is not used), and every checkpoint needs a layer at every one of them on every flight.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/sweepoperatingpoints.md" line="8"/>
        <source>**Why not filter one low-threshold layer by score?** Detect makes one detection per blob of the smoothed heatmap above its threshold, at the blob&apos;s centroid weighted by (value − threshold). Two humps that meet between two thresholds are one blob, hence one detection, at the lower threshold and two at the higher; and every blob&apos;s centroid moves with the threshold. Keeping the low run&apos;s detections scored ≥ t is therefore not a run at t, and the sweep never does it.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/sweepoperatingpoints.md" line="10"/>
        <source>**Definitions**: recall_pre and gmcf_pre exactly as in Evaluate detections (in view, recovered within EPS_PRED_M of a core point, hit clusters), pooled per checkpoint over its flights by micro-averaging (counts summed, one division); every checkpoint must be scored on the same flights. **f1_geo** = 2 · recall · GMCF / (recall + GMCF), the F1 the method prints. **detections_per_frame** = the checkpoint&apos;s detections at that threshold / its frames (processed frames with CHECKPOINTS; the frame layer&apos;s frames with a ground height with DETECTIONS).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/sweepoperatingpoints.md" line="12"/>
        <source>**Credibility filter**: a configuration is credible when the mean number of geotags per hit cluster is at most MAX_GEOTAGS_PER_HIT (default 1.5: above it, one &quot;cluster&quot; swallows several surveyed targets) and the mean of the clusters&apos; median extents is at most MAX_MEAN_EXTENT_M (default 1.0 m: above it, DBSCAN is chaining unrelated detections across the field). Both means are pooled over flights (sums over all hit clusters, or all clusters, divided once). A configuration without any hit cluster is not credible.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/sweepoperatingpoints.md" line="14"/>
        <source>**Pareto front**: the credible configurations, of any checkpoint, that no other credible one beats on both recall_pre and gmcf_pre (at least as good on both, better on one). Configurations with identical scores are all kept.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/sweepoperatingpoints.md" line="16"/>
        <source>**The default grid is the method&apos;s**: 14,400 configurations per checkpoint, holding every operating point the method reports (thresholds 0.03 to 0.12 and 0.035, the threshold of its lowest-review-burden arm; EPS 0.10, 0.15 and 0.20 m; MIN_SAMPLES 2, 5, 10 and 20; EPS_PRED 0.20 and 0.35 m). 14,400 = 12 thresholds × 10 EPS × 12 MIN_SAMPLES × 10 EPS_PRED:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/sweepoperatingpoints.md" line="18"/>
        <source>- THRESHOLDS `0.03,0.035,0.04,0.045,0.05,0.06,…,0.12` (12: half steps up to 0.05, where the method&apos;s arms lie and where the detections per frame change fastest, then steps of 0.01);
- EPS_M `0.025,0.05,…,0.25` (10, steps of 0.025 m, so 0.10, 0.15 and 0.20 are grid points, and one step beyond the largest);
- MIN_SAMPLES `1,2,…,10,15,20` (12);
- EPS_PRED_M `0.05,0.1,…,0.5` (10, steps of 0.05 m, so 0.20 and 0.35 are grid points).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/sweepoperatingpoints.md" line="23"/>
        <source>The method states the named values and the total; the values in between are ours. To reproduce the method&apos;s figures, also set Minimum points count to *cells*. With several checkpoints the table has 14,400 rows per checkpoint.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/sweepoperatingpoints.md" line="25"/>
        <source>## Parameters</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/sweepoperatingpoints.md" line="27"/>
        <source>- **ONNX checkpoints** or **Detection layers** (not both), **Frame layers**, **Geotags**: as above.
- **Thresholds** (probabilities, with CHECKPOINTS), **EPS_M** (m), **MIN_SAMPLES**, **EPS_PRED_M** (m): comma-separated lists, e.g. `0.05,0.1,0.2`.
- **De-duplication grid cell (cm)** (default 3), **Minimum points count** (CORE_COUNT, advanced: detections by default, or cells as the method counts; see Cluster detections) and **edge buffer (px)** (default 0: the in-view test, and with CHECKPOINTS the detections dropped that close to the image border, as Detect&apos;s EDGE_BUFFER_PX), fixed for the whole sweep.
- **Terrain model (DEM)**, **DEM heights are measured from**, **geoid undulation N (m)**, **Ground model without a DEM** (GROUND_MODEL, advanced): as in Detect targets. With CHECKPOINTS the detections are placed on this ground and the in-view test stands on it, so the sweep scores what Detect with the same parameters would write. With DETECTIONS each flight is scored on the ground its layers record (all of a flight&apos;s layers on one ground); the DEM is needed for layers placed on one and refused for layers placed on a plane, and GROUND_MODEL is not used.
- **Credible: mean geotags per hit cluster at most** (default 1.5) and **mean median cluster extent at most (m)** (default 1.0).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/sweepoperatingpoints.md" line="33"/>
        <source>Work is reused across the grid (per checkpoint, flight and threshold the detections are de-duplicated once; DBSCAN runs once per EPS_M and MIN_SAMPLES), with exactly the numbers Evaluate detections gives for the same detections and configuration.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/sweepoperatingpoints.md" line="35"/>
        <source>## Outputs</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/sweepoperatingpoints.md" line="37"/>
        <source>- **Configurations (CSV)**: one row per configuration: checkpoint, model_digest, threshold, eps_m, min_samples, eps_pred_m, n_frames, n_detections, detections_per_frame, the pooled counts, recall_pre, gmcf_pre, f1_geo, mean_geotags_per_hit_cluster, mean_median_extent_m, credible, pareto, dedup_cm, core_count, edge_buffer_px.
- **JSON** (read by Select arms): the checkpoints, flights, grid (with dedup_cm, core_count and edge_buffer_px), credibility limits, the Pareto configurations and all rows. Arms chosen from a sweep made before core_count was recorded count cells, as that sweep did.
- **Frontier plot (PNG)**: gmcf_pre against recall_pre; grey crosses are not credible, the red line is the Pareto front.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>help:terrainslope</name>
    <message>
        <location filename="../resources/help/terrainslope.md" line="1"/>
        <source>Labels are placed with a level-ground model: every target is assumed to lie at the height of the ground straight below the drone. On a slope that is not true. This study gives the label error in pixels for an uphill target (the worst case) against the terrain slope and the target&apos;s horizontal distance from the point below the drone, and the steepest slope that keeps labels within your tolerance at the farthest edge midpoints and corner of the frame. In pixels the error does not depend on the altitude (it depends on distance / altitude); the altitude only converts the frame points to metres.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/terrainslope.md" line="3"/>
        <source>**Camera**: a **platform preset** (its camera; see Sensor bound), a **calibration** file (Kalibr or OpenCV YAML; it overrides the typed intrinsics) or **fx, fy, cx, cy** [px] and **image width, height** [px].</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/terrainslope.md" line="5"/>
        <source>- **Altitude** [m]: height above the ground under the drone; &gt; 0.
- **Label tolerance r** [px]: the label error you accept; drawn as the red contour.
- **Steepest slope studied** [degrees]: the upper end of the slope axis, between 0 and 90 (default 45).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/terrainslope.md" line="9"/>
        <source>## Outputs</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/terrainslope.md" line="11"/>
        <source>- **Results (JSON)**: `slopes_deg` (every 0.5°), `distance_ratios` (ρ = distance / altitude, 101 steps to 15 % beyond the frame corner), `error_px` (rows = slopes, columns = ρ; null where the target would be level with the camera), and `frame_points` with, for the farthest left/right edge midpoint (`edge_u`), top/bottom edge midpoint (`edge_v`) and corner, `distance_ratio`, `distance_m` and `max_slope_deg` (the steepest uphill slope within the tolerance).
- **Contour plot (PNG)**: label error over slope × ρ, the tolerance contour in red, the frame&apos;s edge and corner ρ as dashed lines.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>help:traindetector</name>
    <message>
        <location filename="../resources/help/traindetector.md" line="1"/>
        <source>Trains a heatmap detector on one or more Write training labels folders (their tiles and soft labels) and writes an ONNX model that Detect targets runs, with the full BirdsEye/Deepness metadata (resolution, tile size, overlap, normalisation, default threshold, label σ), a model card and a plot of the training and validation loss.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/traindetector.md" line="3"/>
        <source>PyTorch never runs inside QGIS: training runs in a separate Python process, which reports its progress, losses and validation figures line by line to the progress bar and this log. Cancel ends that process (and anything it started) cleanly: it writes its last checkpoint (`&lt;model&gt;.checkpoint.pt`, kept) and no model is written. A crash or an out-of-memory end is reported with its cause and the last lines the process wrote.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/traindetector.md" line="5"/>
        <source>The training uses PyTorch from BirdsEye › Install dependencies…, group **PyTorch (training)** (the CPU build, or the CUDA build where an NVIDIA driver is present), installed into its own folder of your QGIS profile; or a Python you name (PYTHON) that has torch, onnx and OpenCV. Without one the algorithm says what to install. It trains on the GPU when PyTorch sees one, else on the CPU.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/traindetector.md" line="7"/>
        <source>With the **Fast** preset (the default) each tile is resampled from its frame&apos;s ground sample distance to the model&apos;s resolution, as the detector resamples frames. Training runs in two stages on the time budget: 20 % with the encoder frozen, then every layer fine-tuned, on random 96 px crops with flips, quarter turns, scale and colour jitter. Validation holds out frames that share no target with training (VALIDATION) — at 5 frames/s each target is in many frames, so frames held out at random would show the network the targets it trained on. At the end, the trained network is exported as the model will be and run with Detect targets&apos; own detector over the held-out frames&apos; full images; its detections are clustered and scored as Evaluate detections scores a flight: **recall** (held-out targets recovered) and **GMCF** (clusters on a target) per threshold, and the default threshold is chosen from them. The held-out tiles&apos; figures remain in the model card as a diagnostic; they do not predict a flight.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/traindetector.md" line="9"/>
        <source>A labels set without a tile holding a target is refused (no model is written). When nothing is held out (too few targets, blocks or flights, VALIDATION nothing) or the held-out frames cannot be scored on the ground (no frame layer, only a GSD), the log and the model card warn that the default threshold was not validated on the ground.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/traindetector.md" line="11"/>
        <source>The **Method** preset follows the published method&apos;s recipe instead: an EfficientNetV2 encoder under a transposed-convolution decoder, 224 × 224 crops of tiles kept at their frames&apos; own ground sample distance (no resampling), two stages (encoder frozen, then its top 30 % of blocks unfrozen), AdamW at 1e-5 (β 0.9/0.999), plain binary cross-entropy, and early stopping: a stage ends after 15 epochs (passes over the training tiles) without a lower validation loss and goes back to its best epoch&apos;s weights, or at its share of the time budget, whichever comes first — the model card says which ended it. The method names EfficientNetV2-B3; torchvision offers EfficientNetV2 from S up, so the preset trains `efficientnet_v2_s`, the nearest.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/traindetector.md" line="13"/>
        <source>## Parameters</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/traindetector.md" line="15"/>
        <source>- **LABELS** — Write training labels output folders written with a tile size (`tiles/images`, `tiles/labels`); pick the folder or any file in it (e.g. its `summary.json`); in a model or a script, a list of them, or text joining them with `;`. `labels.csv` decides which tiles hold a target (a label&apos;s u, v inside the tile); its `label` column names the model&apos;s class — the one class all labels share, or, since the heatmap has one output channel that cannot tell classes apart, every class joined by `+` (e.g. `burrow+nest`; the log says so). Its `provenance` column (survey, review), when present, is counted in the model card.
- **FRAMES** — the frame layers the labels were written from: each frame&apos;s `gsd_cm` (ground sample distance, cm/px), and its pose and image, with which the held-out frames are run through the detector and scored on the ground. One per labels folder in the same order, or one for all. Tiles of frames without a GSD are left out (counted in the log).
- **GSD_CM** — instead of frame layers: one ground sample distance (cm/px) for every frame. The frames&apos; poses are then unknown: the threshold is chosen on the held-out tiles, with a warning.
- A folder of **Write training labels on a raster** needs neither: it carries the raster&apos;s GSD, which its tiles take whatever FRAMES or GSD_CM say for the other folders. Each of its tiles is a frame; spatial blocks hold out part of the raster, and its held-out tiles are scored as tiles (there are no frames to run the detector over).
- **PRESET** — *Fast (default)*: the settings described first above, with the BACKBONE and RESOLUTION_CM you choose. *Method (EfficientNetV2, two stages, AdamW)*: the method&apos;s recipe; it sets the network (`efficientnet_v2_s`, so BACKBONE is not used) and trains at the frames&apos; own GSD (RESOLUTION_CM is not used: the model runs at the training frames&apos; median GSD). Its ImageNet weights come from WEIGHTS or torchvision&apos;s cache only; without them the encoder starts from random initialisation and the model card says plainly that it is not ImageNet-pretrained. At 1e-5, with 224 px crops through a larger network, it needs many more steps than Fast: give it a long budget and let early stopping end it.
- **BACKBONE** — `small` (the default): the recipe&apos;s own small encoder–decoder, trained from scratch, works offline. Or an ImageNet-pretrained torchvision encoder (EfficientNet B0–B3, EfficientNetV2-S, ResNet-18/34/50) under a light decoder; slower per step, better features for few labels.
- **WEIGHTS** — the pretrained encoder&apos;s ImageNet weights (.pth, a torchvision state dict). Empty: torchvision&apos;s cache (`~/.cache/torch/hub/checkpoints`, the file name torchvision uses). Nothing is downloaded; when the file is in neither place the run stops and says which file to put where.
- **INIT** — fine-tune from the weights (`&lt;model&gt;.pt`) of an earlier training with the same backbone, e.g. a model trained on simulated campaigns adapted to real labels. No ImageNet weights are needed then. A BirdsEye ONNX model of the small network (the bundled `birdseye_demo_heatmap.onnx`, or any model this algorithm wrote) serves too: its weights are read back from the ONNX graph and checked against onnxruntime&apos;s output; the batch norms the export folded into convolutions keep their statistics frozen while their scale and shift still learn, and stay frozen when you fine-tune again from the `.pt` that run wrote. The new model keeps the earlier model&apos;s resolution and normalisation (mean, std, channel order); a `.pt` written by an older BirdsEye records neither, and the run then trains at RESOLUTION_CM normalised as a new model (the log says so). When part of the frames is held out and scored on the ground, the starting model is scored on them too: if the fine-tuned model&apos;s best F1 there is lower, the starting weights are kept (written as the new model, with their figures and threshold) and the log and the model card say so — a round of fine-tuning never hands on a model that does worse on the held-out ground than the one it started from.
- **MINUTES** — training time budget in minutes (default 20); loading tiles, validation and export come on top.
- **RESOLUTION_CM** — the model&apos;s resolution in cm/px. Empty (the default): the INIT model&apos;s, else 1.0. A value other than the INIT model&apos;s resolution is refused: its filters learnt targets of a size in pixels. Not used by the Method preset, which trains at the frames&apos; own GSD.
- **VALIDATION** — what is held out. *Spatial blocks* (default): the targets (`targets.csv` of each labels folder) are grouped into square ground blocks one frame footprint diagonal wide and whole blocks are held out; frames that see only held-out targets validate, frames that see only training targets train, frames that see both are dropped (counted in the model card); frames that see no target follow the block of their footprint&apos;s centre. A block is held out in every labels folder, so two flights over one site keep each target on one side. *Whole flights*: whole labels folders held out (needs two or more). *Nothing*: every frame trains; the threshold is not validated. A labels folder written before `targets.csv` existed is split by random frames instead, with a warning.
- **VALIDATION_FRACTION** — share of the targets held out, 0–0.5 (default 0.15): blocks (or flights) are taken in a random order while their targets fit under it (the smallest alone when none fits).
- **SEED** — random seed of the split, the crops and the initial weights.
- **THRESHOLD** (advanced) — default threshold written into the model; empty: chosen on the ground figures of the held-out frames — the highest threshold whose F1 (harmonic mean of recall and GMCF) is within one target&apos;s worth (1 / held-out targets in view) of the best without finding fewer held-out targets than the best, i.e. the fewest detections among F1 values the held-out targets cannot tell apart, never at the cost of a target. Without ground figures, the same rule on the held-out tiles&apos; F1, with a warning; 0.5 when neither found a target.
- **THREADS** (advanced) — CPU threads for training; 0 uses every core.
- **PYTHON** (advanced) — a Python interpreter with torch, onnx, OpenCV (and torchvision for a pretrained encoder, matplotlib for the plot, onnxruntime and scipy for the validation on the ground). Empty: the environment variable BIRDSEYE_TRAINING_PYTHON, else QGIS&apos;s Python with the folder Install dependencies installed PyTorch into.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/traindetector.md" line="32"/>
        <source>## Outputs</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/traindetector.md" line="34"/>
        <source>- **OUTPUT_MODEL** — the ONNX model (written under a temporary name and renamed at the end: a cancelled or failed run leaves none).
- **MODEL_CARD** — `&lt;model&gt;.md`: the data (folders, tiles, positives, negatives, targets by provenance), the preset and its settings, how the encoder started (ImageNet weights, or random initialisation), what ended each stage (time budget, early stopping), training time and device, the validation split (method; targets, frames and tiles on each side; frames dropped; warnings), the ground figures per threshold (recall, GMCF, F1, clusters) and the held-out tiles&apos; figures (recall, precision, F1, false detections per tile; peaks and targets matched one to one). `&lt;model&gt;.training.json` holds the same in `split`, `ground_validation`, `validation`, `threshold_rule`, `validated_on` and `warnings`.
- **PLOT** — `&lt;model&gt;_loss.png`: training and validation loss against training time (s).
- **CHECKPOINT** — `&lt;model&gt;.pt`: the final weights, for INIT.
- **TILES, THRESHOLD_USED, TRAIN_SECONDS, TILES_PER_SECOND** — for models and scripts.
- **VALIDATION_RECALL, VALIDATION_GMCF** — the ground figures of the held-out frames at the default threshold (empty when not measured).</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>help:writelabels</name>
    <message>
        <location filename="../resources/help/writelabels.md" line="1"/>
        <source>Projects every surveyed geotag into every frame that sees it and writes a training set — no image clicking. Each frame places the geotags on the ground it sees (the level plane at the tilt-corrected altimeter depth), so the rover&apos;s antenna height never moves a label; labels are in the original, distorted image (OpenCV pixel convention: pixel (0, 0) is the centre of the top-left pixel).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/writelabels.md" line="3"/>
        <source>**Frames of a camera solution** (Import camera solution, flag `geotag_heights`: Metashape, COLMAP in ECEF or ENU) have no altimeter: there each geotag is projected at its own surveyed ellipsoidal height (the rover&apos;s `altWGS84`, or MSL + undulation); a geotag without a height goes onto the DEM if given, else onto a level plane at the median height of the surveyed geotags. Refined frames (Refine frame poses) and OpenDroneMap solutions place geotags on the ground their tie points show. Frames that could not be refined (flag `not_refined`) keep the drone&apos;s metadata pose and are named in a warning: their labels are only as good as that metadata.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/writelabels.md" line="5"/>
        <source>## Parameters</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/writelabels.md" line="7"/>
        <source>- **Geotags**: any point layer, usually the output of Import geotags. An `id` field names each geotag (each its own; without the field, the row number 1.. in feature order) and a `label` field its class (else &quot;target&quot;).
- **Frames**: a frame layer from Import flight log or Import drone images (it carries poses and the camera model).
- **Soft-label σ (px)**: the Gaussian&apos;s standard deviation; default 10 px (the method&apos;s: a 30 px radius at 3σ). **SENSOR_BOUND_JSON**, when given, sets σ = r/3 from a saved sensor-bound run instead; the sensor-bound calculator&apos;s *Write labels with this σ…* opens this dialog with its σ filled in.
- **σ from a sensorbound result**: a JSON written by the Sensor bound algorithm: σ = r / 3 with r its label tolerance; refused if the budget is rejected at any altitude.
- **Where σ comes from** (SIGMA_SOURCE): *Given* (default) — SIGMA_PX, or r / 3 of SENSOR_BOUND_JSON when you give one; or *Measured* — the error of your labels measured on a **label check** (MARK_CHECK): the layer *Label check (pinned image marks)* that Import camera solution writes when the solution has control points with marks a person pinned in the images (saved to any file QGIS opens). σ is then the per-axis RMS of the distance label − mark, √(mean(Δu² + Δv²) / 2) in px: the sensor bound sizes a label of radius 3σ for an error of standard deviation σ in each image direction, and a radius of 3σ holds 98.9 % of such an error. Check points (not used by the adjustment) are used when the check has any, else the control points (the log warns: they flatter the labels); marks without a label are left out and counted. With fewer than 10 marks the log says how uncertain σ is (about ±1/√(4n)).
- **Edge buffer (px)**: a geotag that projects inside the image but closer than this to its border is reported as &quot;edge&quot; and not written as a label (default 0).
- **Write one soft-label raster per frame**: `rasters/&lt;frame_id&gt;.png`, the image&apos;s size, 8 bit: 255·exp(−r²/2σ²) out to r = 3σ, overlapping humps combined by max.
- **Tiled training set**: image and label tiles side by side in `tiles/images` and `tiles/labels` (tile size in px, default 224; the last row and column of tiles sit flush with the border). Every tile holding a label is kept; negative tiles are sampled with the seed, this many per positive tile (at least one per frame). No tile that might show a target without its label is written (see &quot;No tile teaches a target as background&quot; below).
- **Surveyed area** (SURVEYED_AREA, optional): polygons you draw around the ground the survey searched (any polygon layer, any CRS; holes allowed). Without it, the surveyed area is the convex hull of the geotags grown by **SURVEY_MARGIN_M** (m, default 1 m: about what a surveyor walking to the outermost targets also looked at; more would let unsurveyed ground in — draw the area to say more).
- **Target relief h (m)** (RELIEF_M, optional) for the relief check (below): how far the targets stand above the ground their labels are placed on (a mound, a plant). Without it, and with a DEM, each target&apos;s h is the DEM&apos;s height range (highest − lowest) within 1 m of it — simple on purpose, an upper bound, and where the labels stand on that DEM they already follow the relief it shows. Without either the check is skipped.
- **COCO-keypoints JSON**: `coco_keypoints.json`, one &quot;centre&quot; keypoint per label, pixel-centre coordinates.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/writelabels.md" line="19"/>
        <source>## No tile teaches a target as background</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/writelabels.md" line="21"/>
        <source>A negative tile (label all zero) tells the network &quot;nothing here&quot;. A target in such a tile without its label teaches it that a target is background. So, with tiles:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/writelabels.md" line="23"/>
        <source>- A tile is **not written** (positive or not) when, within the label radius (3σ) of it, lies a target in view but not labelled: one inside the edge buffer, one whose centre lies just beyond the image border but whose label disc reaches in, or a cluster the review left unresolved (it may be a target).
- A frame without a ground height (no altimeter reading: it gets no labels) gets **no tiles**: what it shows is unknown.
- A tile **without a positive** is written only when its whole footprint on the ground lies inside the surveyed area: outside it, a target nobody surveyed may lie there. Tiles with a positive are kept anywhere.
- A geotag without a position (an empty geometry) could lie in any tile: writing tiles is refused, naming its row; give it a position or remove it. Without tiles it is left out with a warning.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/writelabels.md" line="28"/>
        <source>`summary.json` counts the tiles skipped for each reason (`tiles.skipped`). Targets hidden behind terrain (with a DEM) are not in the image, so their tiles show background truly. The per-frame rasters and the COCO file cover whole frames and carry no such marks: train from the tiles.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/writelabels.md" line="30"/>
        <source>## Relief check</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/writelabels.md" line="32"/>
        <source>A target standing h above the ground its label was placed on, at horizontal distance r from the camera&apos;s nadir and d below the camera, appears moved outwards by h·r/d on the ground (to first order; e.g. 0.52 m of relief at r = 2.5 m and d = 10 m moves it 13 cm), that is h·r/d · f/d px with f the focal length in px. For a nadir camera r is the label&apos;s distance from the image centre, taken to the ground. A frame is reported when one of its labels moves by more than the label radius 3σ: the log names the first frames (px and cm), `summary.json` (`relief`) lists them all with h, r, d and the displacement, and **RELIEF_FRAMES_OVER** counts them. The exact move is larger by d/(d − h) (5.5 % at 0.52 m from 10 m): the check is a screen, not a correction.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/writelabels.md" line="34"/>
        <source>## Verdicts become labels (optional)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/writelabels.md" line="36"/>
        <source>- **Review verdicts** (REVIEW): the review dock&apos;s verdict table (`birdseye_verdicts` of the review GeoPackage), as in Evaluate detections. **Detection layers the review judged** (REVIEW_DETECTIONS): the outputs of Detect targets on these frames. Their clusters are made and matched to the geotags exactly as Evaluate detections does, and each gets the outcome of all its judgements (direct and propagated):
  - **confirmed real** (every vote says so) **and matched by no geotag**: a target nobody surveyed. It is labelled like a geotag, at the cluster&apos;s centroid (the mean of its detections) placed on the ground each frame sees, in every frame that sees it; `provenance` review, id `&lt;detection layer&gt;#&lt;cluster id&gt;`, the survey&apos;s class when the survey has one class (else `target`).
  - **hard negative** (every vote says so): frames that see it get no label there; a negative tile holding it is a *hard-negative tile* (label all zero) and is drawn before the other negatives when negatives are sampled (NEGATIVE_RATIO per positive tile, at least one per frame).
  - **uncertain**, **unreviewed**, and **conflicting** (votes on both sides) clusters are not labelled, and no tile near one is written — Plan the survey flight flies back to them. Clusters a geotag matches keep the geotag&apos;s label whatever the review says.
- **DEDUP_CM** (cm, default 3), **EPS_M** (m, default 0.20), **MIN_SAMPLES** (default 2), **CORE_COUNT** (default detections), **EPS_PRED_M** (m, default 0.20) — advanced: the clustering and matching the review was scored with (the review dock&apos;s values); the in-view test uses the edge buffer above.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/writelabels.md" line="42"/>
        <source>## Outputs</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/writelabels.md" line="44"/>
        <source>- `labels.csv`: frame_id, image, geotag_id, label, u, v, sigma_px, margin_px (distance to the nearest image edge, px), provenance (`survey`: a geotag; `review`: a confirmed cluster no geotag matches) — one row per target per frame in view.
- `labels.txt`: the reference payload&apos;s format, one line per labelled frame: `idx path u,v,cls u,v,cls …` (cls = index in `summary.json`&apos;s classes).
- `targets.csv`: one row per target written to `labels.csv`: `geotag_id, label, provenance, lat, lon` (WGS84 degrees), `height_m, height_ref` (the target&apos;s height in the reference it carries: `ellipsoidal` for a geotag; empty for a review target, which has none).
- `summary.json`: frames with labels, labels per frame, frames per geotag, geotags never in view, edge cases (`n_edge`, `n_beyond_border`, `n_unresolved_in_view`); `sigma_px`, `label_radius_px` and `sigma_source` (which σ and where it came from: `given`, `sensor_bound` with its file, or `mark_check` with its file, the marks used and their RMS per axis); `surveyed_area` (drawn, or the geotags&apos; hull and its margin); `provenance` (targets, targets in view and labels of the survey and of the review), `hard_negatives` (clusters, in view, frames that see one); with tiles, the tiles written (positive, negative, hard negative) and skipped (`tiles.skipped`: near a target not labelled, outside the surveyed area, frames without a ground height); `relief` (the relief check).
- **REVIEW_TARGETS**, **HARD_NEGATIVES**: how many confirmed clusters became targets and how many hard negatives were found. **SIGMA_USED_PX**: the σ used (px). **RELIEF_FRAMES_OVER**: frames failing the relief check.
- **Frames with label counts** and **Geotags with frames seen**: copies of the input layers with an `n_labels` / `frames_seen` field. Your input layers are not modified.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/writelabels.md" line="51"/>
        <source>## Terrain</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/writelabels.md" line="53"/>
        <source>- **Terrain model (DEM)**: optional raster in a projected CRS. With it, geotags sit on the terrain and each frame&apos;s view is intersected with it (labels behind a ridge are dropped); without it, each frame sees a level plane at the altimeter depth, which the method measured to hold up to about 10° of slope near the image centre (the Terrain slope algorithm tells where it breaks for your camera).
- **DEM heights are measured from**: ellipsoidal, mean sea level, or unknown. The frame layer says what its own heights are measured from (field `height_ref`: ellipsoidal for a pose log, EGM96 — above mean sea level — for DJI and other drone images) and where each frame&apos;s ground came from (`ground_src`); the DEM is converted into the frames&apos; heights before anything is compared. Between ellipsoidal and mean-sea-level heights that needs the geoid undulation N (ellipsoidal = MSL + N): **Geoid undulation N (m)** when you give it, else PROJ&apos;s EGM96 grid where the frames name EGM96 (installed with QGIS on most systems; if it is not, the run stops, naming the grid and how to install it). A mean-sea-level DEM with DJI frames needs no N.
- **The DEM check.** The converted DEM must agree with the frames&apos; own ground: where it was measured under each frame (altimeter, tie points of Refine frame poses) the median difference must lie within a few per cent of the flight height (3 %, at least 0.2 m: ±0.3 m at 10 m, ±1.2 m at 40 m); where it is a take-off point (DJI&apos;s relative altitude, a flight height), that height must be one the DEM&apos;s terrain has within 500 m of the frames, within the same tolerance. The offset found is written to the log either way; a DEM beyond it is refused, naming the offset. A DEM of unknown reference is taken as the frames&apos; and accepted only when that check passes.
- **Ground model without a DEM** (advanced, GROUND_MODEL): *Level ground at the tilt-corrected altimeter depth* (default; the better model of a level field) or *the method&apos;s plane*, normal to the optical axis at the raw altimeter reading, as the method placed its labels — choose it to reproduce the method&apos;s figures. Over level ground the two agree at the image centre and part where the camera is tilted: with the deployed camera (1920 × 1200 px, fx 4264 px) tilted 3° in roll, a label at the left or right edge moves by 14.1 or 8.6 px and at a corner by 11–16 px; tilted 3° in pitch, by 6.0 or 2.8 px at the top or bottom edge and 8–9 px at a corner (the same at any altitude). The method&apos;s plane needs every frame&apos;s radar reading: frames flagged `no_ground_height`, and DJI frames (no radar altimeter), are refused with their ids — leave them out of the frame layer (select `&quot;flags&quot; NOT LIKE &apos;%no_ground_height%&apos;` and use the selected features only). It cannot be combined with a DEM.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>help:writelabelsraster</name>
    <message>
        <location filename="../resources/help/writelabelsraster.md" line="1"/>
        <source>Puts every surveyed geotag on a raster layer — an orthomosaic from OpenDroneMap/WebODM, DJI Terra, Pix4D or a service provider — and writes a training set of tiles cut from it: the same folder Write training labels writes, so Train detector trains on it as it is, or on it and frame folders together.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/writelabelsraster.md" line="3"/>
        <source>Each geotag lands at the pixel the raster&apos;s georeferencing gives its position (pixel (0, 0) is the centre of the top-left pixel; no camera, no ground model). The raster is read tile by tile through QGIS&apos;s raster provider, never whole: a 20,000 × 20,000 px orthomosaic needs the memory of one tile. The progress bar moves per tile written and Cancel stops between tiles.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/writelabelsraster.md" line="5"/>
        <source>The orthomosaic must agree with the survey: a target is labelled where the survey says it is, so a raster shifted against the survey (no ground control points, a different datum) teaches the detector the wrong place. Check a few targets on the map over the raster before you write labels, and give σ large enough to cover what remains.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/writelabelsraster.md" line="7"/>
        <source>## Parameters</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/writelabelsraster.md" line="9"/>
        <source>- **RASTER** — the raster, north up, in a projected CRS in metres or feet (a raster in degrees is refused: reproject it with Raster › Projections › Warp to the field&apos;s UTM zone). Pixels at the bands&apos; no-data value, or transparent in an alpha band (OpenDroneMap&apos;s RGBA orthophotos), count as no data.
- **GEOTAGS** — any point layer, usually the output of Import geotags: an `id` field names each geotag (without it, the row number 1.. in feature order) and a `label` field its class (else &quot;target&quot;). A geotag without a position could lie in any tile: the run is refused, naming its row.
- **Soft-label σ on the ground (cm)** (SIGMA_CM) — the Gaussian&apos;s standard deviation on the ground, default 5 cm (a label radius 3σ of 15 cm). It becomes σ px = σ cm / the raster&apos;s ground sample distance (cm/px, from its pixel size): 5 cm on a 1.25 cm/px orthomosaic is 4 px. The log gives σ in px; it warns under one pixel.
- **Tile size (px)** — the side of the tiles, in the raster&apos;s pixels, default 224. Tiles lie on a regular grid from the top-left corner; the last row and column sit flush with the raster&apos;s border.
- **Negative tiles kept per positive tile** — tiles without a target, drawn at random with the **seed**: this many per tile with a target (as many as for one such tile when there is none).
- **Surveyed area** (SURVEYED_AREA, optional) — polygons you draw around the ground the survey searched (any polygon layer, any CRS; holes allowed). Without it, the convex hull of the geotags grown by **SURVEY_MARGIN_M** (m, default 1 m). A tile without a target is written only when its whole outline lies inside: outside, a target nobody surveyed may lie there. Tiles with a target are kept anywhere.
- **BANDS** (advanced) — the bands read as red, green and blue, in that order (three bands, or one band for all three). Empty: bands 1, 2, 3, or band 1 three times for a single-band raster.
- **VALUE_RANGE** (advanced) — for a raster that is not 8-bit (16-bit, floating point): the value written as 0 and the value written as 255, for every band. Empty: each band&apos;s 2 %–98 % cumulative cut, from a sample of the raster (QGIS&apos;s own default stretch); the log says the ranges used.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/writelabelsraster.md" line="18"/>
        <source>## Verdicts become labels (optional)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/writelabelsraster.md" line="20"/>
        <source>- **Review verdicts** (REVIEW): the review dock&apos;s verdict table (`birdseye_verdicts` of the review GeoPackage), as in Evaluate detections. **REVIEW_DETECTIONS** — the detection layer(s) the review judged (outputs of Detect targets on the frames of a flight over this field); **REVIEW_FRAMES** — their frame layers, one per detection layer, in the same order. The clusters are made and matched to the geotags exactly as Evaluate detections does, and each gets the outcome of all its judgements:
  - **confirmed real** (every vote says so) **and matched by no geotag**: a target nobody surveyed, labelled at the cluster&apos;s centroid (the mean of its detections&apos; positions) on the raster; `provenance` review, the survey&apos;s class when it has one (else `target`); no height in `targets.csv`.
  - **hard negative**: a negative tile holding it is drawn before the other negatives.
  - **uncertain**, **unreviewed** and **conflicting** clusters are not labelled, and no tile within 3σ of one is written.
- **DEDUP_CM** (cm, default 3), **EPS_M** (m, default 0.20), **MIN_SAMPLES** (default 2), **CORE_COUNT** (default detections), **EPS_PRED_M** (m, default 0.20), **EDGE_BUFFER_PX** (px, default 0) — advanced: the clustering and matching the review was scored with (the review dock&apos;s values).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/writelabelsraster.md" line="26"/>
        <source>## No tile teaches a target as background</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/writelabelsraster.md" line="28"/>
        <source>- A geotag outside the raster, or on a pixel without data (a hole in the orthomosaic), is not labelled; no tile within the label radius 3σ of it is written (its label disc may reach in, and the tile would show part of it as background). The log names these geotags.
- A tile without a target is written only inside the surveyed area (above), and only when it holds a pixel with data; pixels without data are black in the tiles.
- No tile within 3σ of a cluster the review left unresolved is written (above).
- The labels of a tile show every labelled target whose label disc reaches into it, also one whose centre lies in the next tile.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/writelabelsraster.md" line="33"/>
        <source>## Outputs</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/writelabelsraster.md" line="35"/>
        <source>The label folder, laid out as Write training labels lays it out:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/writelabelsraster.md" line="37"/>
        <source>- `tiles/images`, `tiles/labels` — image tiles (8-bit) and label tiles (8 bit: 255·exp(−r²/2σ²) out to r = 3σ, r in px, overlapping humps combined by max), named `&lt;frame_id&gt;_&lt;y0&gt;_&lt;x0&gt;.png`: **each tile is one frame**, `frame_id` its number on the tile grid (row by row) and (x0, y0) its top-left pixel in the raster.
- `labels.csv` — frame_id, image (the raster&apos;s file), geotag_id, label, u, v (the target&apos;s column and row in the raster, px), sigma_px, margin_px (distance to the tile&apos;s nearest edge, px; negative for a target outside the tile whose label reaches in), provenance (`survey`: a geotag; `review`: a confirmed cluster no geotag matches) — one row per target per tile its label shows.
- `labels.txt` — one line per tile with a target: `frame_id path u,v,cls …`, u, v in the tile&apos;s pixels.
- `targets.csv` — the targets labelled: `geotag_id, label, provenance, lat, lon` (WGS84 degrees), `height_m, height_ref` (the geotag&apos;s own height, `ellipsoidal`; empty for a review target; the raster carries none).
- `summary.json` — tiles written (with a target, negative) and skipped (`tiles.skipped`: near a target not labelled or an unresolved cluster, outside the surveyed area, drawn without data), hard-negative tiles, geotags outside the raster or on no data, `sigma_cm`, `sigma_px`, `label_radius_px`, `surveyed_area`, and `raster`: its file, CRS, size, pixel size and **`gsd_cm`**, the ground sample distance Train detector resamples the tiles from.
- **LABEL_COUNT**, **POSITIVE_TILES**, **NEGATIVE_TILES**, **GEOTAGS_NOT_LABELLED**, **SIGMA_USED_PX** (px of the raster), **REVIEW_TARGETS**, **HARD_NEGATIVES** — for models and scripts.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/writelabelsraster.md" line="44"/>
        <source>## Training on it</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../resources/help/writelabelsraster.md" line="46"/>
        <source>Give the folder to Train detector as any labels folder. It needs no frame layer and no GSD: it reads the raster&apos;s GSD from `summary.json` (whatever frame layer or GSD_CM is given for other folders). With spatial blocks (the default validation) the blocks are a tile&apos;s ground diagonal wide and the tiles are held out by the targets they show, so no target is on both sides; tiles without a target follow their neighbour in their row. The default threshold is then chosen on the held-out tiles (there are no frames to run the detector over as a flight), and the log says so: score the model on a flight it never saw with Evaluate detections before relying on it.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
</TS>
