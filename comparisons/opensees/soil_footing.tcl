# An upliftlab scene on Gajan and Kutter's contact interface model, for Tcl OpenSees.
#
# Written unchanged by `upliftlab opensees SCENE` for a scene whose foundation is the
# macro-element (foundation.law = "macro"): this file holds no number and no text of the scene.
# The scene's numbers are in model_numbers.txt beside it ("name value" per line, each checked to
# be a number before anything is built), the ground acceleration (in g, one value per line at
# the record's step) in motion_g.txt, and how each part corresponds to upliftlab's element in
# model.md. Run it with `OpenSees model.tcl` (Tcl OpenSees: openseespy has no
# soilFootingSection2d). It writes footing.out (time, u, v, theta of the footing centre),
# story.out (time, u of the story mass) and section.out (time, the section's V, H, M) beside
# itself.
#
# The model, 2D with three DOFs per node, in the scene's consistent units:
#   node 1, the ground (fixed; the motion enters as a uniform excitation);
#   node 2, the footing centre, on a zeroLengthSection of soilFootingSection2d from node 1
#     (local x pointing down, so that the section's V is positive in compression), beside a
#     horizontal dashpot (the footing's sway dashpot, when the scene has one);
#   node 3, the story mass at the story height, on an elastic column from node 2 whose rotation
#     is tied to the footing's (equalDOF): a shear story k = 12 E I / h^3 on a rigid base;
#     its dashpot is stiffness-proportional on that column (c = beta k);
#   masses: the story's horizontal mass at node 3; at node 2 the footing's horizontal mass,
#     the whole vertical mass W_v/g and the structure's rotary inertia about the base.
# Gravity in load steps; one static step of a horizontal load of 1e-6 of the story weight, put
# on and taken off (the section otherwise returns NaN on the first dynamic step after a purely
# vertical load history); then the motion, Newmark (average acceleration) with Newton.

set here [file dirname [file normalize [info script]]]

set expected {g story_weight vertical_weight height story_stiffness story_damping_beta
              rotary_inertia FS Vult L Kv Kh Rv dL sway_damping dt steps motion_dt
              motion_points has_motion gravity_steps tolerance p_delta}

proc read_numbers {path expected} {
    # The scene's numbers: every expected name once, every value a number; anything else
    # stops the script before a model exists.
    set channel [open $path r]
    set text [read $channel]
    close $channel
    array set numbers {}
    foreach line [split $text "\n"] {
        set line [string trim $line]
        if {$line eq "" || [string index $line 0] eq "#"} {
            continue
        }
        set parts [regexp -all -inline {\S+} $line]
        if {[llength $parts] != 2} {
            error "model_numbers.txt: expected 'name value' on a line, found [llength $parts] words"
        }
        set name [lindex $parts 0]
        set value [lindex $parts 1]
        if {[lsearch -exact $expected $name] < 0} {
            error "model_numbers.txt: an unknown name on a line (expected one of: $expected)"
        }
        if {[info exists numbers($name)]} {
            error "model_numbers.txt: $name is given twice"
        }
        if {![string is double -strict $value]} {
            error "model_numbers.txt: the value of $name is not a number"
        }
        set numbers($name) $value
    }
    foreach name $expected {
        if {![info exists numbers($name)]} {
            error "model_numbers.txt: $name is missing"
        }
    }
    return [array get numbers]
}

array set N [read_numbers [file join $here model_numbers.txt] $expected]

wipe
model BasicBuilder -ndm 2 -ndf 3

node 1 0.0 0.0
node 2 0.0 0.0
node 3 0.0 $N(height)
fix 1 1 1 1

set story_mass [expr {$N(story_weight) / $N(g)}]
set footing_mass [expr {($N(vertical_weight) - $N(story_weight)) / $N(g)}]
set vertical_mass [expr {$N(vertical_weight) / $N(g)}]
mass 2 $footing_mass $vertical_mass $N(rotary_inertia)
mass 3 $story_mass 0.0 0.0

# the contact interface model under the footing centre
section soilFootingSection2d 1 $N(FS) $N(Vult) $N(L) $N(Kv) $N(Kh) $N(Rv) $N(dL)
element zeroLengthSection 1 1 2 1 -orient 0.0 -1.0 0.0 1.0 0.0 0.0
if {$N(sway_damping) > 0.0} {
    uniaxialMaterial Viscous 1 $N(sway_damping) 1.0
    element zeroLength 2 1 2 -mat 1 -dir 1
}

# the story: a column of unit E whose I gives the shear stiffness with its ends' rotations tied
set column_E 1.0
set column_I [expr {$N(story_stiffness) * pow($N(height), 3) / (12.0 * $column_E)}]
set column_A [expr {1.0e6 * $N(Kv) * $N(height) / $column_E}]
if {$N(p_delta) > 0.5} {
    geomTransf PDelta 1
} else {
    geomTransf Linear 1
}
element elasticBeamColumn 3 2 3 $column_A $column_E $column_I 1
equalDOF 2 3 3
if {$N(story_damping_beta) > 0.0} {
    region 1 -ele 3 -rayleigh 0.0 0.0 $N(story_damping_beta) 0.0
}

# gravity
timeSeries Linear 1
pattern Plain 1 1 {
    load 3 0.0 [expr {-$N(story_weight)}] 0.0
    load 2 0.0 [expr {$N(story_weight) - $N(vertical_weight)}] 0.0
}
constraints Transformation
numberer RCM
system UmfPack
test NormDispIncr $N(tolerance) 50
algorithm Newton
integrator LoadControl [expr {1.0 / $N(gravity_steps)}]
analysis Static
if {[analyze [expr {int($N(gravity_steps))}]] != 0} {
    error "gravity did not converge"
}
loadConst -time 0.0

# a horizontal load step, put on and taken off
timeSeries Constant 2
pattern Plain 2 2 {
    load 3 [expr {1.0e-6 * $N(story_weight)}] 0.0 0.0
}
integrator LoadControl 1.0
if {[analyze 1] != 0} {
    error "the horizontal load step did not converge"
}
remove loadPattern 2
if {[analyze 1] != 0} {
    error "taking the horizontal load step off did not converge"
}
loadConst -time 0.0
wipeAnalysis

# the motion
if {$N(has_motion) > 0.5} {
    timeSeries Path 3 -dt $N(motion_dt) -filePath [file join $here motion_g.txt] -factor $N(g)
    pattern UniformExcitation 3 1 -accel 3
}
recorder Node -file [file join $here footing.out] -time -node 2 -dof 1 2 3 disp
recorder Node -file [file join $here story.out] -time -node 3 -dof 1 disp
recorder Element -file [file join $here section.out] -time -ele 1 force

constraints Transformation
numberer RCM
system UmfPack
test NormDispIncr $N(tolerance) 50
algorithm Newton
integrator Newmark 0.5 0.25
analysis Transient
set steps [expr {int($N(steps))}]
for {set i 1} {$i <= $steps} {incr i} {
    if {[analyze 1 $N(dt)] != 0} {
        error "step $i of $steps did not converge"
    }
}
wipe
puts "model.tcl: $steps steps of $N(dt) s; wrote footing.out, story.out and section.out"
